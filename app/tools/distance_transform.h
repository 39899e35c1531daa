// Exact Euclidean distance transforms (Felzenszwalb & Huttenlocher 2012, separable lower
// envelope of parabolas), used for the 2D medial axis of a picture (seed 002 §3.1.1.1) and the
// depth below a model's surface (the soft boundary of model → cloud).
#pragma once

#include <cstdint>
#include <vector>

namespace cb {

// Squared distance of every pixel of a width×height grid to the nearest pixel with
// feature[i] != 0, and (if nearest != nullptr) that pixel's index. Without any feature every
// distance is +inf and every index −1.
void squaredDistance2d(int width, int height, const std::vector<uint8_t>& feature,
                       std::vector<float>* squared, std::vector<int>* nearest);

// Squared distance (in voxels) of every cell of an nx×ny×nz grid (x fastest) to the nearest
// cell with feature[i] != 0. Rows are processed in parallel (deterministic: disjoint writes).
void squaredDistance3d(int nx, int ny, int nz, const std::vector<uint8_t>& feature,
                       std::vector<float>* squared);

}  // namespace cb
