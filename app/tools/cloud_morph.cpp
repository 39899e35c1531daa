#include "app/tools/cloud_morph.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/core/parallel_for.h"
#include "app/mapping/stroke_random.h"
#include "app/tools/tool_error.h"

namespace cb {
namespace {

// One particle per non-empty cell (its density-weighted centre) and each cell's particle index
// (−1 for an empty cell). Cell layers are summed in parallel, each voxel in x, y, z order.
void cellParticles(const Volume& v, const MorphParams& p, glm::ivec3 cells,
                   std::vector<glm::vec3>* particles, std::vector<int>* cell_particle) {
  const glm::ivec3 d = v.dims();
  const int cv = p.cell_voxels;
  const size_t layer = size_t(cells.x) * cells.y;
  std::vector<glm::dvec4> acc(layer * cells.z, glm::dvec4(0));
  parallelFor(size_t(cells.z), 1, [&](size_t, size_t cz_begin, size_t cz_end) {
    std::vector<float> row(size_t(d.x));
    for (size_t cz = cz_begin; cz < cz_end; ++cz)
      for (int z = int(cz) * cv; z < std::min(d.z, int(cz + 1) * cv); ++z)
        for (int y = 0; y < d.y; ++y) {
          v.readLine({0, y, z}, 0, d.x, row.data());
          glm::dvec4* cell_row = &acc[cz * layer + size_t(y / cv) * cells.x];
          for (int x = 0; x < d.x; ++x) {
            const float m = row[x];
            if (m <= p.density_threshold) continue;
            cell_row[x / cv] += glm::dvec4(glm::dvec3(x + 0.5, y + 0.5, z + 0.5) * double(m), m);
          }
        }
  });
  cell_particle->assign(acc.size(), -1);
  for (size_t i = 0; i < acc.size(); ++i)
    if (acc[i].w > 0) {
      (*cell_particle)[i] = int(particles->size());
      particles->push_back(glm::vec3(glm::dvec3(acc[i]) / acc[i].w));
    }
}

// §3.3.1 for |from| ≤ |to|: rounds in which each `from` particle, in order, takes its nearest
// unpaired `to` particle, while at least |from| remain; the rest each join their nearest
// `from` particle (the seed's reverse mapping). Pairs are (from index, to index).
std::vector<std::pair<int, int>> greedyPairs(const std::vector<glm::vec3>& from,
                                             const std::vector<glm::vec3>& to) {
  std::vector<std::pair<int, int>> pairs;
  std::vector<uint8_t> taken(to.size(), 0);
  size_t left = to.size();
  while (left >= from.size()) {
    for (size_t i = 0; i < from.size(); ++i) {
      float best = std::numeric_limits<float>::infinity();
      int best_j = -1;
      for (size_t j = 0; j < to.size(); ++j) {
        if (taken[j]) continue;
        const glm::vec3 d = to[j] - from[i];
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
      const glm::vec3 d = to[j] - from[i];
      const float d2 = glm::dot(d, d);
      if (d2 < best) best = d2, best_i = int(i);
    }
    pairs.emplace_back(best_i, int(j));
  }
  return pairs;
}

// A trilinear splat at continuous index p (voxel centres at integers), clamped to the grid.
void splat(glm::vec3 p, float mass, Volume* out) {
  const glm::ivec3 dims = out->dims();
  p = glm::clamp(p, glm::vec3(0.0f), glm::vec3(dims - 1));
  const glm::ivec3 b = glm::min(glm::ivec3(glm::floor(p)), dims - 1);
  const glm::vec3 f = p - glm::vec3(b);
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o((c & 1), (c >> 1) & 1, (c >> 2) & 1);
    const glm::ivec3 q = glm::min(b + o, dims - 1);
    const float w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
    if (w == 0.0f) continue;
    out->voxelForWrite(q.x, q.y, q.z) += w * mass;
  }
}

// The cells' mean displacements (times 1 for a non-empty cell, 0 for an empty one) on a grid
// padded by one empty cell on every side, so interpolation needs no bounds checks; and each
// cell's number of paths (1 for an empty cell).
struct CellDisplacements {
  glm::ivec3 padded;
  std::vector<glm::vec4> u, v;
  std::vector<uint32_t> paths;

  CellDisplacements(glm::ivec3 cells, const MorphPlan::Side& side) : padded(cells + 2) {
    const size_t padded_count = size_t(padded.x) * padded.y * padded.z;
    u.assign(padded_count, glm::vec4(0));
    v.assign(padded_count, glm::vec4(0));
    paths.assign(size_t(cells.x) * cells.y * cells.z, 1);
    for (int z = 0; z < cells.z; ++z)
      for (int y = 0; y < cells.y; ++y)
        for (int x = 0; x < cells.x; ++x) {
          const size_t c = (size_t(z) * cells.y + y) * cells.x + x;
          const int particle = side.cell_particle[c];
          if (particle < 0) continue;
          u[index(x, y, z)] = glm::vec4(side.mean_u[size_t(particle)], 1.0f);
          v[index(x, y, z)] = glm::vec4(side.mean_v[size_t(particle)], 1.0f);
          paths[c] = uint32_t(side.particle_paths[size_t(particle)].size());
        }
  }
  size_t index(int x, int y, int z) const {
    return (size_t(z + 1) * padded.y + size_t(y + 1)) * padded.x + size_t(x + 1);
  }
};

}  // namespace

MorphPlan::MorphPlan(const Volume& source, const Volume& target, const MorphParams& params)
    : params_(params),
      dims_(source.dims()),
      cells_((source.dims() + params.cell_voxels - 1) / params.cell_voxels),
      world_min_(source.worldMin()),
      world_max_(source.worldMax()) {
  if (source.dims() != target.dims() || source.worldMin() != target.worldMin() ||
      source.worldMax() != target.worldMax())
    throw ToolError(ToolErrorKind::kMismatchedVolumes,
                    "source and target must share dims and world box");
  std::vector<glm::vec3> ps, pt;
  cellParticles(source, params, cells_, &ps, &source_.cell_particle);
  cellParticles(target, params, cells_, &pt, &target_.cell_particle);
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
  for (auto [s, t] : pairs) max_dis = std::max(max_dis, glm::distance(ps[s], pt[t]));
  source_.particle_paths.resize(ps.size());
  target_.particle_paths.resize(pt.size());
  paths_.reserve(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto [s, t] = pairs[k];
    const glm::vec3 S = ps[s], T = pt[t];
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
    source_.particle_paths[s].push_back(uint32_t(k));
    target_.particle_paths[t].push_back(uint32_t(k));
  }
  // Each particle's mean displacement vectors (U, V of the header) over its paths.
  for (bool from_source : {true, false}) {
    Side& side = from_source ? source_ : target_;
    side.mean_u.assign(side.particle_paths.size(), glm::vec3(0));
    side.mean_v.assign(side.particle_paths.size(), glm::vec3(0));
    for (size_t i = 0; i < side.particle_paths.size(); ++i) {
      for (uint32_t k : side.particle_paths[i]) {
        const Path& p = paths_[k];
        side.mean_u[i] += from_source ? p.refine - p.source : p.source - p.target;
        side.mean_v[i] += from_source ? p.target - p.source : p.refine - p.target;
      }
      const float n = float(std::max<size_t>(1, side.particle_paths[i].size()));
      side.mean_u[i] /= n;
      side.mean_v[i] /= n;
    }
  }
}

CloudMorph::CloudMorph(const Volume& source, const Volume& target, const MorphParams& params)
    : CloudMorph(std::make_shared<const MorphPlan>(source, target, params), source, target) {}

CloudMorph::CloudMorph(std::shared_ptr<const MorphPlan> plan, const Volume& source,
                       const Volume& target)
    : plan_(std::move(plan)), blank_(source.dims(), source.worldMin(), source.worldMax()) {
  for (const Volume* v : {&source, &target})
    if (v->dims() != source.dims() || glm::any(glm::greaterThan(v->dims(), plan_->dims())) ||
        v->worldMin() != plan_->worldMin() || v->worldMax() != plan_->worldMax())
      throw ToolError(ToolErrorKind::kMismatchedVolumes,
                      "a morph carries clouds on its planned grid or a coarser one over the same "
                      "world box");
  carry(source, true);
  source_items_ = items_.size();
  carry(target, false);
}

void CloudMorph::carry(const Volume& cloud, bool from_source) {
  const MorphPlan& plan = *plan_;
  const MorphPlan::Side& side = plan.side(from_source);
  const glm::ivec3 d = cloud.dims(), cells = plan.cells();
  const glm::vec3 to_plan = glm::vec3(plan.dims()) / glm::vec3(d);
  const glm::vec3 to_carried = glm::vec3(d) / glm::vec3(plan.dims());
  const float cv = float(plan.params().cell_voxels);
  const float threshold = plan.params().density_threshold;
  const CellDisplacements cell(cells, side);
  const glm::ivec3 padded = cell.padded;
  const std::vector<glm::vec4>&cell_u = cell.u, &cell_v = cell.v;
  const std::vector<uint32_t>& cell_paths = cell.paths;
  auto paddedIndex = [&](int x, int y, int z) { return cell.index(x, y, z); };
  auto ownCell = [&](float p, int n) { return std::clamp(int(std::floor(p / cv)), 0, n - 1); };
  // Per z plane: how many splats, then where each plane's splats start.
  std::vector<size_t> plane_items(size_t(d.z) + 1, 0);
  parallelFor(size_t(d.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    std::vector<float> row(size_t(d.x));
    for (int z = int(z_begin); z < int(z_end); ++z) {
      const int cz = ownCell((float(z) + 0.5f) * to_plan.z, cells.z);
      size_t n = 0;
      for (int y = 0; y < d.y; ++y) {
        const int cy = ownCell((float(y) + 0.5f) * to_plan.y, cells.y);
        const uint32_t* paths = &cell_paths[(size_t(cz) * cells.y + cy) * cells.x];
        cloud.readLine({0, y, z}, 0, d.x, row.data());
        for (int x = 0; x < d.x; ++x)
          if (row[x] > threshold) n += paths[ownCell((float(x) + 0.5f) * to_plan.x, cells.x)];
      }
      plane_items[size_t(z) + 1] = n;
    }
  });
  const size_t first = items_.size();
  for (int z = 0; z < d.z; ++z) plane_items[size_t(z) + 1] += plane_items[size_t(z)];
  items_.resize(first + plane_items[size_t(d.z)]);
  parallelFor(size_t(d.z), 4, [&](size_t, size_t z_begin, size_t z_end) {
    // One row's cells blended over y and z (the trilinear weights of the two rows and planes
    // of cell centres around it), so each voxel only blends two of them along x.
    std::vector<glm::vec4> row_u(size_t(padded.x)), row_v(size_t(padded.x));
    std::vector<float> row(size_t(d.x));
    for (int z = int(z_begin); z < int(z_end); ++z) {
      const float pz = (float(z) + 0.5f) * to_plan.z;
      const float gz = pz / cv - 0.5f;
      const int cz0 = int(std::floor(gz));
      const float fz = gz - float(cz0);
      const int own_z = ownCell(pz, cells.z);
      const float win_z =
          std::clamp(2.0f - 4.0f * std::abs(pz / cv - (float(own_z) + 0.5f)), 0.0f, 1.0f);
      CarriedSplat* out = items_.data() + first + plane_items[size_t(z)];
      for (int y = 0; y < d.y; ++y) {
        cloud.readLine({0, y, z}, 0, d.x, row.data());
        bool any = false;
        for (int x = 0; x < d.x && !any; ++x) any = row[x] > threshold;
        if (!any) continue;
        const float py = (float(y) + 0.5f) * to_plan.y;
        const float gy = py / cv - 0.5f;
        const int cy0 = int(std::floor(gy));
        const float fy = gy - float(cy0);
        const int own_y = ownCell(py, cells.y);
        const float win_yz =
            win_z * std::clamp(2.0f - 4.0f * std::abs(py / cv - (float(own_y) + 0.5f)), 0.0f, 1.0f);
        for (int cx = -1; cx <= cells.x; ++cx) {
          const glm::vec4 u = (1 - fz) * ((1 - fy) * cell_u[paddedIndex(cx, cy0, cz0)] +
                                          fy * cell_u[paddedIndex(cx, cy0 + 1, cz0)]) +
                              fz * ((1 - fy) * cell_u[paddedIndex(cx, cy0, cz0 + 1)] +
                                    fy * cell_u[paddedIndex(cx, cy0 + 1, cz0 + 1)]);
          const glm::vec4 v = (1 - fz) * ((1 - fy) * cell_v[paddedIndex(cx, cy0, cz0)] +
                                          fy * cell_v[paddedIndex(cx, cy0 + 1, cz0)]) +
                              fz * ((1 - fy) * cell_v[paddedIndex(cx, cy0, cz0 + 1)] +
                                    fy * cell_v[paddedIndex(cx, cy0 + 1, cz0 + 1)]);
          row_u[size_t(cx + 1)] = u;
          row_v[size_t(cx + 1)] = v;
        }
        const int* own_row = &side.cell_particle[(size_t(own_z) * cells.y + own_y) * cells.x];
        for (int x = 0; x < d.x; ++x) {
          const float m = row[x];
          if (m <= threshold) continue;
          const float px = (float(x) + 0.5f) * to_plan.x;
          const float gx = px / cv - 0.5f;
          const int cx0 = int(std::floor(gx));
          const float fx = gx - float(cx0);
          const glm::vec4 u = (1 - fx) * row_u[size_t(cx0 + 1)] + fx * row_u[size_t(cx0 + 2)];
          const glm::vec4 v = (1 - fx) * row_v[size_t(cx0 + 1)] + fx * row_v[size_t(cx0 + 2)];
          // w: the weight of the non-empty cells (> 0 whenever the voxel's own cell is one).
          const glm::vec3 field_u = u.w > 0 ? glm::vec3(u) / u.w : glm::vec3(0);
          const glm::vec3 field_v = v.w > 0 ? glm::vec3(v) / v.w : glm::vec3(0);
          const int own_x = ownCell(px, cells.x);
          const int particle = own_row[own_x];
          const glm::vec3 at0(x, y, z);
          if (particle < 0) {  // a coarse voxel of a cell empty at full resolution
            *out++ = {at0, field_u * to_carried, field_v * to_carried, m};
            continue;
          }
          // The window on the path's own departure: 1 in the inner half, 0 on the faces.
          const float window =
              win_yz *
              std::clamp(2.0f - 4.0f * std::abs(px / cv - (float(own_x) + 0.5f)), 0.0f, 1.0f);
          const std::vector<uint32_t>& paths = side.particle_paths[size_t(particle)];
          const float mass = m / float(paths.size());
          const glm::vec3 mean_u = side.mean_u[size_t(particle)];
          const glm::vec3 mean_v = side.mean_v[size_t(particle)];
          for (uint32_t k : paths) {
            const MorphPlan::Path& p = plan.paths()[k];
            const glm::vec3 pu = from_source ? p.refine - p.source : p.source - p.target;
            const glm::vec3 pv = from_source ? p.target - p.source : p.refine - p.target;
            *out++ = {at0, (field_u + window * (pu - mean_u)) * to_carried,
                      (field_v + window * (pv - mean_v)) * to_carried, mass};
          }
        }
      }
    }
  });
}

glm::vec3 CloudMorph::place(size_t i, float t) const {
  const CarriedSplat& s = items_[i];
  const float a = 1.0f - t;
  const bool from_source = i < source_items_;
  const float c1 = from_source ? 2.0f * a * t : a * a;
  const float c2 = from_source ? t * t : 2.0f * a * t;
  return s.at0 + c1 * s.u + c2 * s.v;
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
      const bool from_source = begin + i < source_items_;
      const glm::vec3 p = glm::clamp(place(begin + i, t), glm::vec3(0.0f), top);
      placed_[i] = {p, (from_source ? 1.0f - t : t) * items_[begin + i].mass};
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
  for (size_t i = 0; i < items_.size(); ++i) {
    const bool from_source = i < source_items_;
    if (from_source ? t >= 1.0f : t <= 0.0f) continue;
    splat(place(i, t), (from_source ? 1.0f - t : t) * items_[i].mass, &out);
  }
  out.markDirty(out.bounds());
  return out;
}

Volume morph(const Volume& source, const Volume& target, float t, const MorphParams& params) {
  return CloudMorph(source, target, params).frame(t);
}

}  // namespace cb
