// Test inputs for the modelling tools: a cloud-like silhouette (a union of discs) as RGBA
// pixels, and hand-made PNG headers for the size checks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cb::test {

// Black discs (the cloud) on white, width×height, opaque. Deterministic.
std::vector<uint8_t> cloudSilhouetteRgba(int width, int height);
// A file holding only a PNG signature and an IHDR chunk claiming width×height.
void writePngHeaderOnly(const std::string& path, uint32_t width, uint32_t height);

}  // namespace cb::test
