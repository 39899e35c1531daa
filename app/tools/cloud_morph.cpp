#include "app/tools/cloud_morph.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/mapping/stroke_random.h"
#include "app/tools/tool_error.h"

namespace cb {
namespace {

struct Particle {
  glm::vec3 position;  // density-weighted cell centre, voxel coordinates
};

// Particles (one per non-empty cell) and each non-empty voxel's cell → particle index.
void cellParticles(const Volume& v, const MorphParams& p, std::vector<Particle>* particles,
                   std::vector<std::pair<size_t, int>>* voxel_particle) {
  const glm::ivec3 d = v.dims();
  const glm::ivec3 cells = (d + p.cell_voxels - 1) / p.cell_voxels;
  std::vector<glm::dvec4> acc(size_t(cells.x) * cells.y * cells.z, glm::dvec4(0));
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const float m = v.at(x, y, z);
        if (m <= p.density_threshold) continue;
        const glm::ivec3 c = glm::ivec3(x, y, z) / p.cell_voxels;
        acc[(size_t(c.z) * cells.y + c.y) * cells.x + c.x] +=
            glm::dvec4(glm::dvec3(x + 0.5, y + 0.5, z + 0.5) * double(m), m);
      }
  std::vector<int> id(acc.size(), -1);
  for (size_t i = 0; i < acc.size(); ++i)
    if (acc[i].w > 0) {
      id[i] = int(particles->size());
      particles->push_back({glm::vec3(glm::dvec3(acc[i]) / acc[i].w)});
    }
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        if (v.at(x, y, z) <= p.density_threshold) continue;
        const glm::ivec3 c = glm::ivec3(x, y, z) / p.cell_voxels;
        voxel_particle->push_back(
            {v.index(x, y, z), id[(size_t(c.z) * cells.y + c.y) * cells.x + c.x]});
      }
}

// §3.3.1 for |from| ≤ |to|: rounds in which each `from` particle, in order, takes its nearest
// unpaired `to` particle, while at least |from| remain; the rest each join their nearest
// `from` particle (the seed's reverse mapping). Pairs are (from index, to index).
std::vector<std::pair<int, int>> greedyPairs(const std::vector<Particle>& from,
                                             const std::vector<Particle>& to) {
  std::vector<std::pair<int, int>> pairs;
  std::vector<uint8_t> taken(to.size(), 0);
  size_t left = to.size();
  while (left >= from.size()) {
    for (size_t i = 0; i < from.size(); ++i) {
      float best = std::numeric_limits<float>::infinity();
      int best_j = -1;
      for (size_t j = 0; j < to.size(); ++j) {
        if (taken[j]) continue;
        const glm::vec3 d = to[j].position - from[i].position;
        const float d2 = glm::dot(d, d);
        if (d2 < best) best = d2, best_j = int(j);
      }
      taken[best_j] = 1;
      --left;
      pairs.emplace_back(int(i), best_j);
    }
  }
  for (size_t j = 0; j < to.size(); ++j) {
    if (taken[j]) continue;
    float best = std::numeric_limits<float>::infinity();
    int best_i = 0;
    for (size_t i = 0; i < from.size(); ++i) {
      const glm::vec3 d = to[j].position - from[i].position;
      const float d2 = glm::dot(d, d);
      if (d2 < best) best = d2, best_i = int(i);
    }
    pairs.emplace_back(best_i, int(j));
  }
  return pairs;
}

void splat(glm::vec3 p, float mass, glm::ivec3 dims, float* out) {
  p = glm::clamp(p - 0.5f, glm::vec3(0.0f), glm::vec3(dims - 1));
  const glm::ivec3 b = glm::min(glm::ivec3(glm::floor(p)), dims - 1);
  const glm::vec3 f = p - glm::vec3(b);
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o((c & 1), (c >> 1) & 1, (c >> 2) & 1);
    const glm::ivec3 q = glm::min(b + o, dims - 1);
    const float w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
    if (w == 0.0f) continue;
    out[(size_t(q.z) * dims.y + q.y) * dims.x + q.x] += w * mass;
  }
}

}  // namespace

CloudMorph::CloudMorph(const Volume& source, const Volume& target, const MorphParams& params)
    : blank_(source.dims(), source.worldMin(), source.worldMax()) {
  if (source.dims() != target.dims() || source.worldMin() != target.worldMin() ||
      source.worldMax() != target.worldMax())
    throw ToolError(ToolErrorKind::kMismatchedVolumes,
                    "source and target must share dims and world box");
  std::vector<Particle> ps, pt;
  std::vector<std::pair<size_t, int>> vs, vt;
  cellParticles(source, params, &ps, &vs);
  cellParticles(target, params, &pt, &vt);
  if (ps.empty() || pt.empty())
    throw ToolError(ToolErrorKind::kEmptyVolume,
                    ps.empty() ? "the source has no density" : "the target has no density");
  std::vector<std::pair<int, int>> pairs;  // (source particle, target particle)
  if (ps.size() <= pt.size()) {
    pairs = greedyPairs(ps, pt);
  } else {
    for (auto [t, s] : greedyPairs(pt, ps)) pairs.emplace_back(s, t);
  }
  // Eq. (10.1)–(10.3): refining points, farther from the chord for shorter paths.
  float max_dis = 0;
  for (auto [s, t] : pairs)
    max_dis = std::max(max_dis, glm::distance(ps[s].position, pt[t].position));
  std::vector<std::vector<uint32_t>> of_source(ps.size()), of_target(pt.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto [s, t] = pairs[k];
    const glm::vec3 S = ps[s].position, T = pt[t].position;
    StrokeRandom rng(params.seed, k);
    const glm::vec3 st = T - S;
    const float dis = glm::length(st);
    glm::vec3 r(float(rng.uniform()) - 0.5f, float(rng.uniform()) - 0.5f,
                float(rng.uniform()) - 0.5f);
    glm::vec3 perp = dis > 0 ? r - st * (glm::dot(r, st) / (dis * dis)) : r;
    const float len = glm::length(perp);
    perp = len > 0 ? perp / len : glm::vec3(0);
    const float h = float(rng.uniform()) * (max_dis - dis) * params.refine_scale;
    paths_.push_back({S, 0.5f * (S + T) + perp * h, T});
    of_source[s].push_back(uint32_t(k));
    of_target[t].push_back(uint32_t(k));
  }
  // Each voxel carries its density along every path of its cell, split evenly.
  auto carry = [&](const Volume& v, const std::vector<std::pair<size_t, int>>& voxels,
                   const std::vector<std::vector<uint32_t>>& of, std::vector<uint32_t>* ids,
                   std::vector<CarriedVoxel>* out) {
    std::vector<uint32_t> first(of.size());
    for (size_t c = 0; c < of.size(); ++c) {
      first[c] = uint32_t(ids->size());
      ids->insert(ids->end(), of[c].begin(), of[c].end());
    }
    const glm::ivec3 d = v.dims();
    for (auto [index, particle] : voxels) {
      const int x = int(index % d.x), y = int((index / d.x) % d.y),
                z = int(index / (size_t(d.x) * d.y));
      const uint32_t count = uint32_t(of[particle].size());
      out->push_back(
          {glm::vec3(x, y, z) + 0.5f, v.data()[index] / float(count), first[particle], count});
    }
  };
  carry(source, vs, of_source, &source_path_ids_, &source_voxels_);
  carry(target, vt, of_target, &target_path_ids_, &target_voxels_);
}

Volume CloudMorph::frame(float t) const {
  t = std::clamp(t, 0.0f, 1.0f);
  Volume out = blank_;
  const glm::ivec3 dims = out.dims();
  float* data = out.data();
  if (t < 1.0f)
    for (const CarriedVoxel& v : source_voxels_)
      for (uint32_t k = 0; k < v.path_count; ++k) {
        const Path& p = paths_[source_path_ids_[v.first_path + k]];
        splat(v.position + (p.at(t) - p.source), (1.0f - t) * v.mass, dims, data);
      }
  if (t > 0.0f)
    for (const CarriedVoxel& v : target_voxels_)
      for (uint32_t k = 0; k < v.path_count; ++k) {
        const Path& p = paths_[target_path_ids_[v.first_path + k]];
        splat(v.position + (p.at(t) - p.target), t * v.mass, dims, data);
      }
  out.markDirty(out.bounds());
  return out;
}

Volume morph(const Volume& source, const Volume& target, float t, const MorphParams& params) {
  return CloudMorph(source, target, params).frame(t);
}

}  // namespace cb
