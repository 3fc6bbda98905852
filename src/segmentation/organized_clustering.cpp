#include "cropsight/segmentation/organized_clustering.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/cpu_dispatch.hpp"
#include "cropsight/core/error.hpp"

namespace cropsight::segmentation {

namespace {

// Link bits (flood_fill.hpp LinkBits) of every pixel from the per-pair rules of OES or ORG
// (within_tolerance, normals_agree: the same functions OesPredicate / OrgPredicate::similar call,
// with p the left / upper pixel), computed row by row in branch-free loops (vectorised; AVX2 clone
// at run time). The rules are symmetric, so the link serves both directions. NaN positions or
// normals compare false: no link.
template <bool kOrg>
inline void row_links(int w, const float* __restrict x, const float* __restrict y, const float* __restrict z,
                      const float* __restrict nx, const float* __restrict ny, const float* __restrict nz, int step,
                      int count, float tol2, float cos_angle, std::uint8_t* __restrict out) {
  for (int i = 0; i < count; ++i) {
    bool ok = within_tolerance(x[i] - x[i + step], y[i] - y[i + step], z[i] - z[i + step], tol2);
    if constexpr (kOrg)
      ok = ok & normals_agree(nx[i], ny[i], nz[i], nx[i + step], ny[i + step], nz[i + step], cos_angle);
    out[i] = std::uint8_t(ok);
  }
}

template <bool kOrg>
CROPSIGHT_AVX2_CLONES void compute_links_impl(int w, int h, const float* x, const float* y, const float* z,
                                              const float* nx, const float* ny, const float* nz,
                                              const std::uint8_t* edges, std::uint8_t barrier, float tol2,
                                              float cos_angle, std::uint8_t* right, std::uint8_t* down,
                                              std::uint8_t* links) {
  const std::size_t n = std::size_t(w) * std::size_t(h);
  // right[i]: pixel i and i + 1 (same row) join; down[i]: i and i + w join.
  for (int v = 0; v < h; ++v) {
    const std::size_t o = std::size_t(v) * w;
    row_links<kOrg>(w, x + o, y + o, z + o, nx + o, ny + o, nz + o, 1, w - 1, tol2, cos_angle, right + o);
    right[o + w - 1] = 0;
  }
  if (h > 1) row_links<kOrg>(w, x, y, z, nx, ny, nz, w, int(n) - w, tol2, cos_angle, down);
  for (std::size_t i = n - std::size_t(w); i < n; ++i) down[i] = 0;
  // Member bit (oes_member / org_member, as the predicates' member()), in its own loop so that it
  // vectorises, then the byte-only combination with right/down of the pixel and left/up from its
  // neighbours (row 0 has no up link, column 0 no left link).
  if constexpr (kOrg) {
    for (std::size_t i = 0; i < n; ++i) links[i] = org_member(z[i], nx[i]) ? kLinkMember : 0;
  } else {
    for (std::size_t i = 0; i < n; ++i) links[i] = oes_member(z[i], edges[i], barrier) ? kLinkMember : 0;
  }
  for (int v = 0; v < h; ++v) {
    const std::size_t o = std::size_t(v) * w;
    const std::uint8_t* up = v > 0 ? down + o - w : down + o;
    const std::uint8_t up_bit = v > 0 ? kLinkUp : 0;
    std::uint8_t* lr = links + o;
    const std::uint8_t* rr = right + o;
    const std::uint8_t* dr = down + o;
    lr[0] = std::uint8_t(lr[0] | rr[0] * kLinkRight | dr[0] * kLinkDown | (up[0] ? up_bit : 0));
    for (int u = 1; u < w; ++u)
      lr[u] =
          std::uint8_t(lr[u] | rr[u] * kLinkRight | rr[u - 1] * kLinkLeft | dr[u] * kLinkDown | (up[u] ? up_bit : 0));
  }
}

// Flood-fill predicate over the link bits (same answers as OrgPredicate).
struct OrgLinks {
  const std::uint8_t* bits;
  const float* curvature;
  float max_curvature;
  bool member(int q) const { return bits[q] & kLinkMember; }
  bool seed(int s) const { return member(s) && expands(s); }
  bool expands(int p) const { return curvature[p] < max_curvature; }
  std::uint8_t links(int p) const { return bits[p]; }
};

// Connected components of the OES link graph, the same result as flood_fill over the link bits (OES
// seeds every member and its links are symmetric, so a fill attempt is exactly the connected
// component of its seed, and attempts are ordered by their first pixel in raster order), computed
// without the per-pixel queue: row runs (members joined by right links) are the nodes of a
// union-find, joined through the up links; the root of a component is its run with the smallest
// index, i.e. the one holding the component's first pixel. Kept components are numbered in the
// order of their roots (= the fill's attempt order); each segment's indices are written run by
// run in raster order (ascending), and ws.labels gets the segment id or -1, as flood_fill does.
// Long on purpose: the clustering's hot path; its run, union and numbering passes share the run arrays.
std::vector<Segment> oes_components(int width, int height, const std::uint8_t* bits, int min_size, int max_size,
                                    int min_size_border, OrganizedClusteringWorkspace& ws) {
  if (width <= 0 || height <= 0) return {};
  const int n = width * height;
  // Run k: runs[2k] = its first pixel, runs[2k + 1] = its length; parent[k]: union-find parent
  // (at most n runs; raw arrays sized once, no per-run push_back).
  if (ws.runs.size() < 2 * std::size_t(n)) ws.runs.resize(2 * std::size_t(n));
  if (ws.parents.size() < std::size_t(n)) ws.parents.resize(std::size_t(n));
  int* runs = ws.runs.data();
  int* parent = ws.parents.data();
  int nruns = 0;
  // Run id per column of the previous and of the current row (-1: not a member).
  if (ws.columns.size() < 2 * std::size_t(width)) ws.columns.resize(2 * std::size_t(width));
  int* prev = ws.columns.data();
  int* cur = prev + width;
  std::fill(prev, prev + width, -1);
  auto find = [parent](int a) {
    while (parent[a] != a) {
      const int up = parent[parent[a]];
      parent[a] = up;  // path halving
      a = up;
    }
    return a;
  };
  for (int v = 0; v < height; ++v) {
    const std::uint8_t* b = bits + std::size_t(v) * width;
    int u = 0;
    while (u < width) {
      if (!(b[u] & kLinkMember)) {
        // Non-members come in long stretches (holes, barriers): 8 at a time while a whole word of
        // link bytes has no member bit.
        constexpr std::uint64_t kMembers = 0x0101010101010101ull * kLinkMember;
        for (std::uint64_t word; u + 8 <= width; u += 8) {
          std::memcpy(&word, b + u, 8);
          if (word & kMembers) break;
          std::fill_n(cur + u, 8, -1);
        }
        if (u < width && !(b[u] & kLinkMember)) cur[u++] = -1;
        continue;
      }
      const int id = nruns++;
      parent[id] = id;
      const int start = u;
      int last_up = -1;
      for (;;) {
        cur[u] = id;
        // Up link to a member above (prev[u] >= 0 only for members; row 0 has no up bit).
        const int above = prev[u];
        if ((b[u] & kLinkUp) && above >= 0 && above != last_up) {
          last_up = above;
          const int ra = find(above), rb = find(id);
          if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
        }
        if (!((b[u] & kLinkRight) && u + 1 < width && (b[u + 1] & kLinkMember))) break;
        ++u;
      }
      ++u;
      runs[2 * id] = v * width + start;
      runs[2 * id + 1] = u - start;
    }
    std::swap(prev, cur);
  }
  // Components in the order of their roots. First every run points at its root directly (roots
  // are final now; a root is the smallest run of its component, so root <= r), then each root gets
  // the next component id in its own entry and every other run reads its root's (already
  // numbered, root < r): parent[] ends as the component of each run.
  for (int r = 0; r < nruns; ++r) parent[r] = find(r);
  std::vector<int>& sizes = ws.sizes;
  sizes.clear();
  for (int r = 0; r < nruns; ++r) {
    const int root = parent[r];
    int c;
    if (root == r) {
      c = int(sizes.size());
      sizes.push_back(0);
    } else {
      c = parent[root];
    }
    sizes[std::size_t(c)] += runs[2 * r + 1];
    parent[r] = c;
  }
  // Components with a run on the image border may use the smaller min_size_border.
  std::vector<char> border;
  if (min_size_border > 0 && min_size_border < min_size) {
    border.assign(sizes.size(), 0);
    for (int r = 0; r < nruns; ++r) {
      const int start = runs[2 * r], v = start / width, u0 = start % width;
      if (v == 0 || v == height - 1 || u0 == 0 || u0 + runs[2 * r + 1] == width) border[std::size_t(parent[r])] = 1;
    }
  }
  std::vector<Segment> out;
  for (std::size_t c = 0; c < sizes.size(); ++c) {
    int& s = sizes[c];
    const int lo = !border.empty() && border[c] ? min_size_border : min_size;
    if (s >= lo && s <= max_size) {
      Segment seg;
      seg.indices.resize(std::size_t(s));
      s = int(out.size());
      out.push_back(std::move(seg));
    } else {
      s = -1;
    }
  }
  ws.labels.assign(std::size_t(n), -1);
  int* labels = ws.labels.data();
  ws.slots.resize(out.size());
  for (std::size_t k = 0; k < out.size(); ++k) ws.slots[k] = out[k].indices.data();
  for (int r = 0; r < nruns; ++r) {
    const int s = sizes[std::size_t(parent[r])];
    if (s < 0) continue;
    const int start = runs[2 * r], len = runs[2 * r + 1];
    int*& slot = ws.slots[std::size_t(s)];
    for (int i = 0; i < len; ++i) labels[start + i] = s, slot[i] = start + i;
    slot += len;
  }
  return out;
}

std::uint8_t* link_buffers(const OrganizedCloud& cloud, OrganizedClusteringWorkspace& ws) {
  ws.links.resize(3 * cloud.size());
  return ws.links.data();
}

void check_sizes(const char* where, float tolerance, int min_size, int max_size) {
  if (!(tolerance > 0.0f)) throw Error(where, "distance_tolerance must be > 0");
  if (min_size < 1 || max_size < min_size) throw Error(where, "size range must satisfy 1 <= min_size <= max_size");
}
}  // namespace

std::vector<Segment> segment_oes(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                 const OesConfig& cfg, OrganizedClusteringWorkspace& ws) {
  check_sizes("oes", cfg.distance_tolerance, cfg.min_size, cfg.max_size);
  if (cfg.min_size_border < 0) throw Error("oes", "min_size_border must be >= 0");
  if (!(cfg.debris_tolerance >= 0.0f)) throw Error("oes", "debris_tolerance must be >= 0");
  if (edges.size() != cloud.size()) throw Error("oes", "edge label image size differs from the cloud size");
  if (cfg.barrier_labels < 0 || cfg.barrier_labels > 255)
    throw Error("oes", "barrier_labels must be a bit mask in 0..255");
  // The flood fill reads precomputed link bits (same answers as OesPredicate, one byte per pixel).
  const std::size_t n = cloud.size();
  std::uint8_t* buf = link_buffers(cloud, ws);
  const float* z = cloud.z.data();
  compute_links_impl<false>(cloud.width, cloud.height, cloud.x.data(), cloud.y.data(), z, z, z, z, edges.data(),
                            std::uint8_t(cfg.barrier_labels), cfg.distance_tolerance * cfg.distance_tolerance, 0.0f,
                            buf + n, buf + 2 * n, buf);
  auto segs = oes_components(cloud.width, cloud.height, buf, cfg.min_size, cfg.max_size, cfg.min_size_border, ws);
  for (auto& s : segs) summarize_raster(s, cloud);
  return segs;
}

std::vector<Segment> segment_org(const OrganizedCloud& cloud, const OrgConfig& cfg, OrganizedClusteringWorkspace& ws) {
  check_sizes("org", cfg.distance_tolerance, cfg.min_size, cfg.max_size);
  if (!cloud.has_normals() || cloud.nx.size() != cloud.size() || cloud.curvature.size() != cloud.size())
    throw Error("org", "the cloud has no normals (estimate them first)");
  if (!(cfg.angle_threshold >= 0.0f && cfg.angle_threshold <= 3.14159265f))
    throw Error("org", "angle_threshold must be in [0, pi] radians");
  // The flood fill reads precomputed link bits (same answers as OrgPredicate, one byte per pixel).
  const std::size_t n = cloud.size();
  std::uint8_t* buf = link_buffers(cloud, ws);
  compute_links_impl<true>(cloud.width, cloud.height, cloud.x.data(), cloud.y.data(), cloud.z.data(), cloud.nx.data(),
                           cloud.ny.data(), cloud.nz.data(), nullptr, 0,
                           cfg.distance_tolerance * cfg.distance_tolerance, std::cos(cfg.angle_threshold), buf + n,
                           buf + 2 * n, buf);
  return flood_fill_segments(cloud, OrgLinks{buf, cloud.curvature.data(), cfg.curvature_threshold}, cfg.min_size,
                             cfg.max_size, ws);
}

}  // namespace cropsight::segmentation
