// The physically based style's light terms as a function of the light volume's transmittance
// T (seed 004, pre-computed lighting), tabulated for the 256 values the GPU copy of T can take
// (RG8), so the shader fetches once per sample instead of a log and four exps.
//
// Entry i (T = i/255, τ = −ln max(T, 1/512)):
//   x = L(τ)        = e^(−τ)·(1 + κ_s·τ)     the light grid with its in-scattering term
//   y = L(b·τ), z = L(b²·τ)                  the multiple-scattering octaves (optical depth ×bⁱ)
//   w = e^(−τ/8)                             the ambient sky's reach into the cloud
// See shaders/shade_physical.glsl for the derivation and the constants' roles.
#pragma once

#include <array>

#include <glm/glm.hpp>

namespace cb {

inline constexpr float kPhysicalInScattering = 0.6f;  // κ_s
inline constexpr float kPhysicalOctaveDepth = 0.5f;   // b
inline constexpr float kPhysicalAmbientFalloff = 0.125f;

std::array<glm::vec4, 256> physicalLightTable();

}  // namespace cb
