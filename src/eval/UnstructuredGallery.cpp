// Real unstructured data (paper Fig. 9): the blunt-fin and spx tetrahedral meshes from the data
// folder, and any mesh given with --mesh, rendered unshaded by VTK's Bunyk, ZSweep and
// projected-tetrahedra renderers and by the MFA model of the mesh's points (with its domain
// mask), with one camera and transfer function per data set.
#include <algorithm>
#include <filesystem>

#include "core/encode/Encoder.h"
#include "core/image/Montage.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"
#include "io/ScatteredLoader.h"

namespace mfadvr::eval {

ExperimentReport runUnstructuredGallery(const EvalContext& ctx) {
  const int image = ctx.quick() ? 192 : 512;
  struct Input {
    std::string path, field;
  };
  std::vector<Input> inputs;
  std::vector<std::string> missing;
  for (const auto& [name, field] : std::vector<std::pair<std::string, std::string>>{
           {"bluntfin_tets.vtu", "Density"}, {"spx.vtk", ""}}) {
    const auto p = ctx.dataFile(name);
    if (p.empty())
      missing.push_back(name);
    else
      inputs.push_back({p.string(), field});
  }
  for (const auto& m : ctx.options().meshes) inputs.push_back({m, ""});

  ExperimentReport report;
  std::string& md = report.markdown;
  md += "Settings: " + std::to_string(image) + "x" + std::to_string(image) +
        " images, perspective framed on the mesh's box, azimuth 30, elevation 20; opacity ramp "
        "over the values' range, cool-to-warm colours, no shading (as the paper's Fig. 9); step "
        "0.5 x the model's data spacing for the MFA model (VTK's tetrahedral renderers integrate "
        "per cell). MFA: degree 3, the encoder's default control counts, smoothing 1e-2, domain "
        "mask from the mesh's cells.\n\n";
  md += ctx.missingDataNote(missing);
  if (inputs.empty()) {
    md += "No meshes to render.\n";
    return report;
  }
  CsvTable table({"dataset", "points", "cells", "method", "render_seconds", "image"});
  std::vector<std::vector<Image8>> rows;
  for (const auto& input : inputs) {
    const std::string name = std::filesystem::path(input.path).stem().string();
    ctx.log("unstructured gallery: " + name + ": loading and encoding");
    ScatteredLoadOptions load;
    load.field.name = input.field;
    ScatteredData mesh;
    try {
      mesh = loadScatteredData(input.path, load);
    } catch (const std::exception& e) {
      report.skipInput(input.path, e.what());  // the rest of the gallery still renders
      continue;
    }
    if (mesh.tets.empty()) {
      md += "`" + input.path +
            "` has no cells (a point cloud): VTK's renderers need cells, skipped.\n\n";
      continue;
    }
    const Model model = encodeScattered(mesh, EncodeOptions{});
    const auto [lo, hi] = std::minmax_element(mesh.values.begin(), mesh.values.end());
    RenderSettings s = sceneSettings(image, image, model.domain().min, model.domain().max, 30.0,
                                     20.0, "ramp", "cool-to-warm", *lo, std::max(*hi, *lo + 1e-12),
                                     model.dataSpacing(), 0.5, ctx.threads());
    const std::string points = std::to_string(mesh.pointCount());
    const std::string cells = std::to_string(mesh.tets.size());
    std::vector<Image8> row;
    auto add = [&](const std::string& method, const TimedImage& r) {
      const std::string path =
          ctx.writeImage("unstructured/" + name + "_" + method + ".png", r.image);
      table.addRow({name + (input.field.empty() ? "" : " (" + input.field + ")"), points, cells,
                    method, csvNumber(r.seconds), path});
      row.push_back(r.image);
    };
    if (ctx.vtk())
      for (VtkMethod m : {VtkMethod::Bunyk, VtkMethod::ZSweep, VtkMethod::ProjectedTetrahedra}) {
        ctx.log("unstructured gallery: " + name + ": " + vtkMethodName(m));
        add(vtkMethodName(m), renderVtk(m, nullptr, &mesh, s, 1));
      }
    ctx.log("unstructured gallery: " + name + ": mfa");
    SceneData scene;
    scene.model = &model;
    MethodSpec spec;
    spec.method = ReconstructionMethod::Mfa;
    add("mfa", renderOurs(scene, spec, s));
    rows.push_back(std::move(row));
  }
  if (rows.empty()) return report;
  table.write(ctx.path("fig09_unstructured.csv").string());
  report.files = {"fig09_unstructured.csv",
                  ctx.writeImage("unstructured/montage.png", montageGrid(rows))};
  md += table.toMarkdown({"dataset", "points", "cells", "method", "render_seconds"},
                         {"data set", "points", "tetrahedra", "method", "render s"}) +
        "\n";
  md += "Compared with the paper:\n\n";
  md += paperBullet(true,
                    "Like the paper's Fig. 9, an image grid to be judged by eye: look for the "
                    "tetrahedral renderers' faceted, cell-shaped features (linear interpolation "
                    "per tetrahedron) against the MFA model's smooth field.");
  md += paperBullet(false,
                    "The paper's unstructured data set (NASA Fun3D retropropulsion, 27,736 "
                    "samples) is not public in a form we have; blunt-fin and spx stand in for it.");
  md +=
      "\nImages: `unstructured/NAME_METHOD.png`; `unstructured/montage.png` rows: the data "
      "sets in the table's order; columns: " +
      std::string(ctx.vtk() ? "vtk-bunyk, vtk-zsweep, vtk-pt, " : "") + "mfa.\n";
  return report;
}

}  // namespace mfadvr::eval
