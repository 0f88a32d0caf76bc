#pragma once
// Numbers the paper publishes (its Tables 1 and 2, Marschner-Lobb; paper section 4.2.1), set
// beside ours in the report. Their setup (grid, camera, image size, step, lighting) is not
// published in full, so they are a reference, not a target.
#include <array>
#include <string>

namespace mfadvr::eval {

struct PaperMetrics {
  const char* method;
  double mse, psnr, ssim;
};

inline constexpr std::array<PaperMetrics, 4> kPaperTable1 = {{{"trilinear", 601.01, 20.34, 0.76},
                                                              {"tricubic", 1097.50, 17.73, 0.79},
                                                              {"catmull-rom", 1099.48, 17.72, 0.79},
                                                              {"mfa", 196.30, 25.20, 0.93}}};

inline constexpr std::array<PaperMetrics, 4> kPaperTable2 = {{{"trilinear", 660.72, 19.93, 0.74},
                                                              {"tricubic", 1174.36, 17.43, 0.77},
                                                              {"catmull-rom", 1176.47, 17.43, 0.77},
                                                              {"mfa", 254.1, 24.08, 0.92}}};

}  // namespace mfadvr::eval
