#pragma once
// Per tile of pixels, the range of ray distances outside which the rays meet no cell that is not
// empty (kernel/DepthBoundsView.h says how a ray uses it). Built once per frame on the CPU from
// the camera and the model's empty-space pyramid:
//
// every aligned block of the pyramid's level L that is not all empty (an "occupied" block) is
// projected onto the image as the box of its occupied sub-blocks of level L - 1 (the cell at
// level 0), which holds every cell of it that is not empty: the rays that cross a box are those
// through the pixels inside its corners' projections when all are in front of the camera (one
// pixel more on each side for rounding); each tile its projection covers keeps the greatest
// distance from the camera to a point of such a box, the kDepthBoxes boxes least distant from the
// camera (by their least distances; every distance is that of the box grown as below) and the
// least distance of the others. A sample farther than the greatest, or nearer than both the least
// of the others and the ray's entry into each kept box it crosses, lies in no occupied block, so
// its cell is empty. (A sample whose location rounds across a block's face into an occupied cell
// lies within a rounding error of that cell's block: the boxes are grown by far more, and the two
// steps of slack of boundSteps cover the distances' rounding.)
//
// L is the finest level with at most kDepthBlocksPerAxis blocks per axis, coarser while the
// projections would cover too many tiles (a camera close to the model), so the build stays a
// small part of the frame.
#include <cstdint>
#include <vector>

#include "core/render/kernel/CameraRays.h"
#include "core/render/kernel/DepthBoundsView.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

// Pixels per tile side.
inline constexpr int kDepthTile = 4;
// The finest level projected has at most this many blocks per axis.
inline constexpr int kDepthBlocksPerAxis = 64;

class DepthBounds {
 public:
  // `view` must carry empty-space flags (view.empty); a masked model's march counts samples
  // outside the mask apart, so its renders take no bounds. blocksPerAxis: the finest level's
  // most blocks per axis (tests take coarser levels with it).
  DepthBounds(const CameraRays& camera, const ModelView& view,
              int blocksPerAxis = kDepthBlocksPerAxis);

  DepthBoundsView view() const {
    return {nearest_.data(),
            farthest_.data(),
            kDepthTile,
            tilesX_,
            tileBoxes_.empty() ? nullptr : tileBoxes_.data(),
            tileKeys_.data(),
            boxes_.data()};
  }
  // The pyramid level whose blocks were projected (0: cells), and how many were occupied.
  int level() const { return level_; }
  std::int64_t occupiedBlocks() const { return occupied_; }

 private:
  std::vector<double> nearest_, farthest_;
  std::vector<std::int32_t> tileBoxes_;  // kDepthBoxes per tile
  std::vector<double> tileKeys_;         // their boxes' least distances
  std::vector<double> boxes_;            // 6 per occupied block
  int tilesX_ = 0;
  int level_ = 0;
  std::int64_t occupied_ = 0;
};

}  // namespace mfadvr
