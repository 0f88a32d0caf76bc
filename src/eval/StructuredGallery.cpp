// Real structured data (paper Fig. 8): fuel, nucleon and bonsai from the data folder, and any
// volume given with --volume, rendered shaded by every grid method, the MFA model and VTK's
// fixed-point ray caster with one camera and transfer function per data set. Real data have no
// ground truth: the result is the image grid (and the render times).
#include <algorithm>
#include <filesystem>

#include "core/encode/Encoder.h"
#include "core/image/Montage.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"
#include "io/VolumeLoader.h"

namespace mfadvr::eval {

ExperimentReport runStructuredGallery(const EvalContext& ctx) {
  const int image = ctx.quick() ? 192 : 512;
  const int maxCtrl = 128;
  std::vector<std::string> inputs;
  std::vector<std::string> missing;
  std::vector<std::string> standard = {"fuel_64x64x64_uint8.raw", "nucleon_41x41x41_uint8.raw"};
  if (!ctx.quick()) standard.push_back("bonsai.nrrd");
  for (const auto& name : standard) {
    const auto p = ctx.dataFile(name);
    if (p.empty())
      missing.push_back(name);
    else
      inputs.push_back(p.string());
  }
  for (const auto& v : ctx.options().volumes) inputs.push_back(v);

  ExperimentReport report;
  std::string& md = report.markdown;
  md += "Settings: " + std::to_string(image) + "x" + std::to_string(image) +
        " images, perspective framed on the box, azimuth 30, elevation 20; opacity ramp over "
        "each volume's range, cool-to-warm colours, shading on (headlight; ambient 0.3, diffuse "
        "0.7, specular 0.2, power 10), step 0.5 x spacing, unit distance 1 spacing. MFA: degree "
        "3, as many control points as samples up to " +
        std::to_string(maxCtrl) +
        " per axis. Real data have no ground truth: compare the images.\n\n";
  md += ctx.missingDataNote(missing);
  if (inputs.empty()) {
    md += "No volumes to render.\n";
    return report;
  }

  std::vector<std::pair<std::string, ReconstructionMethod>> ours = {
      {"trilinear", ReconstructionMethod::Trilinear},
      {"tricubic", ReconstructionMethod::Tricubic},
      {"catmull-rom", ReconstructionMethod::CatmullRom},
      {"bspline", ReconstructionMethod::BSpline},
      {"mfa", ReconstructionMethod::Mfa}};
  CsvTable table({"dataset", "dims", "method", "render_seconds", "image"});
  std::vector<std::vector<Image8>> rows;
  for (const auto& input : inputs) {
    const std::string name = std::filesystem::path(input).stem().string();
    ctx.log("structured gallery: " + name + ": loading and encoding");
    StructuredGrid grid;
    try {
      grid = loadStructuredVolume(input);
    } catch (const std::exception& e) {
      report.skipInput(input, e.what());  // the rest of the gallery still renders
      continue;
    }
    const std::string dims = std::to_string(grid.dims[0]) + "x" + std::to_string(grid.dims[1]) +
                             "x" + std::to_string(grid.dims[2]);
    EncodeOptions fit;
    for (int a = 0; a < 3; ++a)
      fit.controlCounts[a] = static_cast<int>(std::min<std::int64_t>(grid.dims[a], maxCtrl));
    const Model model = encodeStructured(grid, fit);
    const double vmin = *std::min_element(grid.values.begin(), grid.values.end());
    const double vmax = *std::max_element(grid.values.begin(), grid.values.end());
    RenderSettings s = sceneSettings(image, image, grid.boxMin(), grid.boxMax(), 30.0, 20.0, "ramp",
                                     "cool-to-warm", vmin, std::max(vmax, vmin + 1e-12),
                                     grid.spacing, 0.5, ctx.threads());
    s.shade = true;
    SceneData scene;
    scene.grid = &grid;
    scene.model = &model;
    scene.differenceStep = grid.spacing;
    std::vector<Image8> row;
    auto add = [&](const std::string& method, const TimedImage& r) {
      const std::string path =
          ctx.writeImage("structured/" + name + "_" + method + ".png", r.image);
      table.addRow({name, dims, method, csvNumber(r.seconds), path});
      row.push_back(r.image);
    };
    for (const auto& [method, m] : ours) {
      ctx.log("structured gallery: " + name + ": " + method);
      MethodSpec spec;
      spec.method = m;
      add(method, renderOurs(scene, spec, s));
    }
    if (ctx.vtk()) {
      ctx.log("structured gallery: " + name + ": vtk-fixedpoint");
      add("vtk-fixedpoint", renderVtk(VtkMethod::FixedPoint, &grid, nullptr, s, 1));
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty()) return report;
  table.write(ctx.path("fig08_structured.csv").string());
  report.files = {"fig08_structured.csv",
                  ctx.writeImage("structured/montage.png", montageGrid(rows))};
  md += "Render times (s), one frame each:\n\n";
  {
    std::vector<std::string> methods;
    for (const auto& row : table.rows())
      if (std::find(methods.begin(), methods.end(), row[2]) == methods.end())
        methods.push_back(row[2]);
    std::vector<std::string> cols = {"dataset", "dims"};
    cols.insert(cols.end(), methods.begin(), methods.end());
    CsvTable t(cols);
    for (std::size_t i = 0; i < table.rows().size(); i += methods.size()) {
      std::vector<std::string> r = {table.rows()[i][0], table.rows()[i][1]};
      for (std::size_t j = 0; j < methods.size(); ++j)
        r.push_back(fixed(std::stod(table.rows()[i + j][3]), 3));
      t.addRow(r);
    }
    md += t.toMarkdown() + "\n";
  }
  md += "Compared with the paper:\n\n";
  md += paperBullet(true,
                    "Like the paper's Fig. 8, this is an image grid to be judged by eye (no ground "
                    "truth); the paper's observations to look for are trilinear's diamond-shaped "
                    "small features and star-shaped highlights, and the cubic filters' "
                    "overshoot near the volume's boundary.");
  md += paperBullet(false,
                    "The paper's fourth data set, Aneurysm (512^3), is not in the data folder; "
                    "any volume can be added with --volume.");
  md +=
      "\nImages: `structured/NAME_METHOD.png`; `structured/montage.png` rows: the data sets "
      "in the table's order; columns: trilinear, tricubic, catmull-rom, bspline, mfa" +
      std::string(ctx.vtk() ? ", vtk-fixedpoint" : "") + ".\n";
  return report;
}

}  // namespace mfadvr::eval
