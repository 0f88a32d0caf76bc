// Gradient accuracy (paper Table 1) and overall accuracy (Table 2) on Marschner-Lobb, at the two
// grid sizes docs/architecture.md (Evaluation protocol) asks for (64^3, which the paper's trilinear
// figures suggest, and the classic 41^3). Step opacity at the isovalue 0.5, constant white, shading
// on. Table 1 takes the value from the truth and only the gradient from each method; Table 2 takes
// both from the method. The MFA models: degree 3 with as many control points as samples
// (interpolating) and with half as many per axis (the paper's recommendation, section 4.2.3).
#include <cmath>
#include <map>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/image/Montage.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"
#include "eval/PaperReference.h"

namespace mfadvr::eval {

namespace {

struct TableMethod {
  std::string name;
  ReconstructionMethod method;
  const Model* model;
};

// psnr/mse/ssim of one method in one table at one grid.
using Results = std::map<std::string, ImageComparison>;

std::string paperComparison(const std::string& table, const Results& r,
                            const std::array<PaperMetrics, 4>& paper, const std::string& grid) {
  std::string md;
  auto p = [&](const char* m) {
    for (const auto& e : paper)
      if (std::string(e.method) == m) return e;
    return paper[0];
  };
  const double mfa = r.at("mfa").psnr, tri = r.at("trilinear").psnr;
  const double cubic = r.at("tricubic").psnr, cr = r.at("catmull-rom").psnr;
  md += paperBullet(
      mfa > tri && mfa > cubic && mfa > cr,
      table + ", " + grid + ": the MFA model (" + fixed(mfa, 2) + " dB) against trilinear " +
          fixed(tri, 2) + ", tricubic " + fixed(cubic, 2) + ", Catmull-Rom " + fixed(cr, 2) +
          " dB" +
          (mfa > tri && mfa > cubic && mfa > cr
               ? ": best of the four, as in the paper (" + fixed(p("mfa").psnr, 2) + " dB there)."
               : ": not the best of the four, unlike the paper; the images show "
                 "where it loses."));
  md += paperBullet(std::abs(cubic - cr) < 0.05,
                    table + ", " + grid + ": tricubic and Catmull-Rom differ by " +
                        fixed(std::abs(cubic - cr), 3) + " dB" +
                        (std::abs(cubic - cr) < 0.05
                             ? "; with central differences Lekien-Marsden's tricubic is the same "
                               "function as tensor Catmull-Rom, which the paper's equal figures "
                               "also show."
                             : "; they should be the same function with central differences, so "
                               "the difference comes from the boundary (one-sided differences "
                               "in the outermost cells)."));
  const bool paperOrder = tri > cubic;  // the paper has trilinear above the cubic filters
  std::string order = table + ", " + grid + ": trilinear " + (paperOrder ? "above" : "below") +
                      " tricubic (" + fixed(tri, 2) + " vs " + fixed(cubic, 2) + " dB)";
  if (paperOrder) {
    order += ", as in the paper.";
  } else {
    order += "; the paper has trilinear above (" + fixed(p("trilinear").psnr, 2) + " vs " +
             fixed(p("tricubic").psnr, 2) + " dB). ";
    order +=
        "The paper does not publish its grid, view or how its tricubic filter estimates corner "
        "derivatives, so the cause cannot be checked here; in ours the cubic filters' gradients "
        "are continuous across cell faces and trilinear's are not.";
  }
  md += paperBullet(paperOrder, order);
  return md;
}

}  // namespace

ExperimentReport runMarschnerLobbTables(const EvalContext& ctx) {
  const int image = ctx.quick() ? 160 : 512;
  const auto ml = makeBuiltin("marschner-lobb");
  CsvTable table1({"grid", "method", "mse", "psnr", "ssim", "render_seconds", "image"});
  CsvTable table2 = table1;
  std::vector<std::vector<Image8>> rows;
  ExperimentReport report;
  std::string& md = report.markdown;
  std::string comparisons;
  // One step for both grids, so that the truth images are the same: a quarter of the 64^3
  // spacing resolves the function's ripples.
  const double step = 0.25 * 2.0 / 63.0;
  md += "Settings: `marschner-lobb` (fM = 6, alpha = 0.25); " + std::to_string(image) + "x" +
        std::to_string(image) +
        " images, perspective (30 degrees) framed on the box, azimuth 30, elevation 25; opacity "
        "step at 0.5 (of the range [0, 1]), constant white; shading on (headlight; ambient 0.3, "
        "diffuse 0.7, specular 0.2, power 10); step " +
        csvNumber(step, 4) +
        " for every grid; gradient of the grid filters: their own derivative. MFA: degree 3, "
        "`mfa` with as many control points as samples (interpolating), `mfa-half` with half as "
        "many per axis. Metrics on 8-bit RGB against the truth (value and gradient analytic).\n\n";

  for (int n : {64, 41}) {
    const std::string gridName =
        std::to_string(n) + "x" + std::to_string(n) + "x" + std::to_string(n);
    ctx.log("Marschner-Lobb tables: " + gridName + ": sampling and encoding");
    const StructuredGrid grid = sampleBuiltin(*ml, {n, n, n});
    EncodeOptions fit;
    fit.degree = {3, 3, 3};
    fit.controlCounts = {n, n, n};
    const Model full = encodeStructured(grid, fit);
    const int half = n / 2;
    fit.controlCounts = {half, half, half};
    const Model halfModel = encodeStructured(grid, fit);
    const std::vector<TableMethod> methods = {
        {"trilinear", ReconstructionMethod::Trilinear, nullptr},
        {"tricubic", ReconstructionMethod::Tricubic, nullptr},
        {"catmull-rom", ReconstructionMethod::CatmullRom, nullptr},
        {"bspline", ReconstructionMethod::BSpline, nullptr},
        {"mfa", ReconstructionMethod::Mfa, &full},
        {"mfa-half", ReconstructionMethod::Mfa, &halfModel}};

    RenderSettings s =
        sceneSettings(image, image, grid.boxMin(), grid.boxMax(), 30.0, 25.0, "step:0.5", "white",
                      0.0, 1.0, grid.spacing, 0.5, ctx.threads());
    s.sampleDistance = step;
    s.shade = true;

    SceneData base;
    base.grid = &grid;
    base.truth = ml.get();
    base.differenceStep = grid.spacing;
    MethodSpec truthSpec;
    truthSpec.method = ReconstructionMethod::Truth;
    ctx.log("Marschner-Lobb tables: " + gridName + ": truth");
    const TimedImage truth = renderOurs(base, truthSpec, s);
    const std::string truthPath =
        ctx.writeImage("tables/" + std::to_string(n) + "_truth.png", truth.image);
    for (CsvTable* t : {&table1, &table2})
      t->addRow({gridName, "truth", "0", "inf", "1", csvNumber(truth.seconds), truthPath});

    Results r1, r2;
    std::vector<Image8> row1{truth.image}, row2{truth.image};
    for (const TableMethod& m : methods) {
      SceneData scene = base;
      scene.model = m.model;
      for (int t = 1; t <= 2; ++t) {
        ctx.log("Marschner-Lobb tables: " + gridName + ": table " + std::to_string(t) + ", " +
                m.name);
        MethodSpec spec;
        if (t == 1) {
          spec.method = ReconstructionMethod::Truth;
          spec.gradientFrom = m.method;
        } else {
          spec.method = m.method;
        }
        const TimedImage out = renderOurs(scene, spec, s);
        const ImageComparison c = compareImages(truth.image, out.image);
        const std::string path = ctx.writeImage(
            "tables/" + std::to_string(n) + "_table" + std::to_string(t) + "_" + m.name + ".png",
            out.image);
        (t == 1 ? table1 : table2)
            .addRow({gridName, m.name, csvNumber(c.mse), csvNumber(c.psnr), csvNumber(c.ssim),
                     csvNumber(out.seconds), path});
        (t == 1 ? r1 : r2)[m.name] = c;
        (t == 1 ? row1 : row2).push_back(out.image);
      }
    }
    rows.push_back(row1);
    rows.push_back(row2);

    auto section = [&](const std::string& title, const Results& r,
                       const std::array<PaperMetrics, 4>& paper) {
      std::string out = "**" + title + ", " + gridName + "** (MFA: degree 3, " + gridName +
                        " and " + std::to_string(half) + "^3 control points)\n\n";
      out += "| metric |";
      for (const auto& m : methods) out += " " + m.name + " |";
      out += " paper: trilinear | tricubic | Catmull-Rom | MFA |\n|---|";
      for (std::size_t i = 0; i < methods.size() + 4; ++i) out += "---|";
      out += "\n";
      auto line = [&](const char* label, auto ours, auto theirs, int decimals) {
        out += std::string("| ") + label + " |";
        // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on " " + std::string here.
        auto cell = [&](double v) {
          out += ' ';
          out += fixed(v, decimals);
          out += " |";
        };
        for (const auto& m : methods) cell(ours(r.at(m.name)));
        for (const auto& e : paper) cell(theirs(e));
        out += "\n";
      };
      line(
          "MSE", [](const ImageComparison& c) { return c.mse; },
          [](const PaperMetrics& e) { return e.mse; }, 2);
      line(
          "PSNR (dB)", [](const ImageComparison& c) { return c.psnr; },
          [](const PaperMetrics& e) { return e.psnr; }, 2);
      line(
          "SSIM", [](const ImageComparison& c) { return c.ssim; },
          [](const PaperMetrics& e) { return e.ssim; }, 3);
      return out + "\n";
    };
    md += section("Table 1 (gradient only)", r1, kPaperTable1);
    md += section("Table 2 (value and gradient)", r2, kPaperTable2);
    comparisons += paperComparison("Table 1", r1, kPaperTable1, gridName);
    comparisons += paperComparison("Table 2", r2, kPaperTable2, gridName);
  }

  table1.write(ctx.path("table1_gradient.csv").string());
  table2.write(ctx.path("table2_overall.csv").string());
  report.files = {"table1_gradient.csv", "table2_overall.csv",
                  ctx.writeImage("tables/montage.png", montageGrid(rows))};
  md += "Compared with the paper:\n\n" + comparisons;
  md += paperBullet(false,
                    "Absolute values differ from the paper's at both grids: the paper does not "
                    "publish its grid, camera, image size, step or lighting, and MSE and PSNR "
                    "depend on how much of the image the surface covers, so only the order of "
                    "the methods carries over.");
  md +=
      "\nImages: `tables/N_tableT_METHOD.png`; `tables/montage.png` rows: 64^3 Table 1, 64^3 "
      "Table 2, 41^3 Table 1, 41^3 Table 2; columns: truth, trilinear, tricubic, catmull-rom, "
      "bspline, mfa, mfa-half.\n";
  return report;
}

}  // namespace mfadvr::eval
