#include "app/tools/cloud_morph.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/core/parallel_for.h"
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

void splat(glm::vec3 p, float mass, glm::ivec3 dims, Volume& out) {
  p = glm::clamp(p - 0.5f, glm::vec3(0.0f), glm::vec3(dims - 1));
  const glm::ivec3 b = glm::min(glm::ivec3(glm::floor(p)), dims - 1);
  const glm::vec3 f = p - glm::vec3(b);
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o((c & 1), (c >> 1) & 1, (c >> 2) & 1);
    const glm::ivec3 q = glm::min(b + o, dims - 1);
    const float w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
    if (w == 0.0f) continue;
    out.voxelForWrite(q.x, q.y, q.z) += w * mass;
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
  paths_.reserve(pairs.size());
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
                   const std::vector<std::vector<uint32_t>>& of, bool from_source) {
    const glm::ivec3 d = v.dims();
    for (auto [index, particle] : voxels) {
      const int x = int(index % d.x), y = int((index / d.x) % d.y),
                z = int(index / (size_t(d.x) * d.y));
      const float mass = v.at(x, y, z) / float(of[particle].size());
      for (uint32_t k : of[particle]) {
        const glm::vec3 anchor = from_source ? paths_[k].source : paths_[k].target;
        items_.push_back({glm::vec3(x, y, z) + 0.5f - anchor, mass, k});
      }
    }
  };
  carry(source, vs, of_source, true);
  source_items_ = items_.size();
  carry(target, vt, of_target, false);
}

Volume CloudMorph::frame(float t) const {
  Volume out = blank_;
  frameInto(t, &out, {});
  out.markDirty(out.bounds());
  return out;
}

VoxelBox CloudMorph::frameInto(float t, Volume* out, const VoxelBox& previous) const {
  t = std::clamp(t, 0.0f, 1.0f);
  const glm::ivec3 dims = blank_.dims();
  if (out->dims() != dims || out->worldMin() != blank_.worldMin() ||
      out->worldMax() != blank_.worldMax())
    throw ToolError(ToolErrorKind::kMismatchedVolumes,
                    "a morph frame goes into a volume of the source's dims and world box");
  // t = 0 carries only the source, t = 1 only the target (exact ends).
  const size_t begin = t < 1.0f ? 0 : source_items_;
  const size_t end = t > 0.0f ? items_.size() : source_items_;
  const size_t count = end - begin;
  constexpr size_t kChunk = size_t(1) << 16;
  const size_t chunks = chunkCount(count, kChunk);
  const size_t planes = size_t(dims.z);
  placed_.resize(count);
  sorted_.resize(count);
  plane_counts_.assign(chunks * planes, 0);
  std::vector<VoxelBox> chunk_box(chunks);
  const glm::vec3 top(dims - 1);
  auto baseOf = [&](glm::vec3 p) { return glm::min(glm::ivec3(glm::floor(p)), dims - 1); };
  // 1. Place every splat at t; count them per (chunk, base plane).
  parallelFor(count, kChunk, [&](size_t chunk, size_t b, size_t e) {
    uint32_t* counts = &plane_counts_[chunk * planes];
    glm::ivec3 lo(dims), hi(0);
    for (size_t i = b; i < e; ++i) {
      const CarriedSplat& item = items_[begin + i];
      const bool from_source = begin + i < source_items_;
      const glm::vec3 p =
          glm::clamp(item.offset + paths_[item.path].at(t) - 0.5f, glm::vec3(0.0f), top);
      placed_[i] = {p, (from_source ? 1.0f - t : t) * item.mass};
      const glm::ivec3 base = baseOf(p);
      ++counts[base.z];
      lo = glm::min(lo, base);
      hi = glm::max(hi, glm::min(base + 2, dims));
    }
    chunk_box[chunk] = {lo, hi};
  });
  // 2. Stable counting sort by base plane: plane by plane, chunk by chunk, in item order.
  plane_start_.assign(planes + 1, 0);
  size_t offset = 0;
  for (size_t z = 0; z < planes; ++z) {
    plane_start_[z] = offset;
    for (size_t c = 0; c < chunks; ++c) {
      const uint32_t n = plane_counts_[c * planes + z];
      plane_counts_[c * planes + z] = uint32_t(offset);  // now: where chunk c's splats go
      offset += n;
    }
  }
  plane_start_[planes] = offset;
  parallelFor(count, kChunk, [&](size_t chunk, size_t b, size_t e) {
    uint32_t* next = &plane_counts_[chunk * planes];
    for (size_t i = b; i < e; ++i) sorted_[next[baseOf(placed_[i].p).z]++] = placed_[i];
  });
  // 3. Clear what the previous frame wrote, then each plane adds its splats: those based one
  // plane below (their upper corners), then its own (their lower corners).
  const VoxelBox cleared = previous.intersect(out->bounds());
  const std::vector<float> zeros(size_t(std::max(cleared.hi.x - cleared.lo.x, 0)), 0.0f);
  parallelFor(planes, 4, [&](size_t, size_t zb, size_t ze) {
    for (size_t z = zb; z < ze; ++z) {
      if (int(z) >= cleared.lo.z && int(z) < cleared.hi.z)
        for (int y = cleared.lo.y; y < cleared.hi.y; ++y)
          out->writeLine({cleared.lo.x, y, int(z)}, 0, int(zeros.size()), zeros.data());
      for (int upper = 1; upper >= 0; --upper) {
        if (upper && z == 0) continue;
        const size_t from = plane_start_[z - size_t(upper)], to = plane_start_[z - upper + 1];
        for (size_t i = from; i < to; ++i) {
          const PlacedSplat& s = sorted_[i];
          const glm::ivec3 base = baseOf(s.p);
          const glm::vec3 f = s.p - glm::vec3(base);
          const float wz = upper ? f.z : 1.0f - f.z;
          if (wz == 0.0f) continue;
          for (int c = 0; c < 4; ++c) {
            const int ox = c & 1, oy = c >> 1;
            const float w = (ox ? f.x : 1 - f.x) * (oy ? f.y : 1 - f.y) * wz;
            if (w == 0.0f) continue;
            const int qx = std::min(base.x + ox, dims.x - 1),
                      qy = std::min(base.y + oy, dims.y - 1);
            out->voxelForWrite(qx, qy, int(z)) += w * s.mass;
          }
        }
      }
    }
  });
  VoxelBox written;
  for (const VoxelBox& b : chunk_box) written = written.unite(b);
  out->markDirty(written.unite(cleared));
  return written;
}

Volume CloudMorph::frameOneThreadReference(float t) const {
  t = std::clamp(t, 0.0f, 1.0f);
  Volume out = blank_;
  const glm::ivec3 dims = out.dims();
  for (size_t i = 0; i < items_.size(); ++i) {
    const bool from_source = i < source_items_;
    if (from_source ? t >= 1.0f : t <= 0.0f) continue;
    const CarriedSplat& item = items_[i];
    splat(item.offset + paths_[item.path].at(t), (from_source ? 1.0f - t : t) * item.mass, dims,
          out);
  }
  out.markDirty(out.bounds());
  return out;
}

Volume morph(const Volume& source, const Volume& target, float t, const MorphParams& params) {
  return CloudMorph(source, target, params).frame(t);
}

}  // namespace cb
