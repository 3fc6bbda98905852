#pragma once
// The two organised clusterings of Montes et al. 2020 as predicates of the one flood fill
// (flood_fill.hpp):
//
//  OES (organised edge segmentation): regions bounded by organised edges (geometry/
//   organized_edges.hpp). A pixel is a member when it is valid and carries none of the edge
//   labels in `barrier_labels`; 4-neighbours join when their Euclidean distance is below
//   `distance_tolerance` (so two surfaces that touch in the image without an edge pixel between
//   them still separate when they are far apart in 3D).
//  ORG (organised region growing): a pixel is a member when it is valid and has a finite normal;
//   4-neighbours join when the angle between their normals is below `angle_threshold` (and their
//   distance below `distance_tolerance`); growth continues only from pixels whose curvature is
//   below `curvature_threshold` (PCL RegionGrowing's rule), and only such pixels seed segments.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "cropsight/core/organized_cloud.hpp"
#include "cropsight/core/segment.hpp"
#include "cropsight/segmentation/flood_fill.hpp"

namespace cropsight::segmentation {

struct OesConfig {
  float distance_tolerance = 0.01f;  ///< m; max 3D distance between 4-neighbours
  int barrier_labels = 15;  ///< bit mask of geometry::EdgeLabel (1 NaN boundary | 2 occluding | 4 occluded | 8 crease)
  int min_size = 500;       ///< points
  int max_size = 10000;     ///< points
  int min_size_border = 0;  ///< points; minimum for segments touching the image border (0 = min_size)
  float debris_tolerance = 0.0f;  ///< m; > 0: a second pass over the pixels no segment kept (0 = off)

  template <class V>
  void visit(V& v) {
    v("distance_tolerance", distance_tolerance,
      "m; max distance between 4-neighbours of one segment (PCL EuclideanClusterComparator as in its organised "
      "segmentation demo: 0.01 m)");
    v("barrier_labels", barrier_labels,
      "bit mask of edge labels that stop a segment: 1 NaN boundary, 2 occluding, 4 occluded, 8 high curvature (default "
      "15: all)");
    v("min_size", min_size, "points; smaller segments are dropped (paper FEC UK value: 500, Montes et al. 2020)");
    v("max_size", max_size,
      "points; larger segments (ground) are dropped (paper FEC value: 10000, Montes et al. 2020)");
    v("min_size_border", min_size_border,
      "points; smaller minimum for segments with a pixel on the image border, where heads are cut and show "
      "fewer points (ours; 0 = min_size for every segment)");
    v("debris_tolerance", debris_tolerance,
      "m; when > 0, a second pass with this looser tolerance segments the valid pixels that no kept segment holds "
      "(pieces below min_size): a rough or noisy surface that the first tolerance shattered into debris gets a "
      "segment, while what the first pass separated stays separated (ours; 0 = off, the paper's one pass)");
  }
};

struct OrgConfig {
  float angle_threshold = 0.0872665f;  ///< rad (5°); max angle between neighbouring normals
  float curvature_threshold = 0.05f;   ///< surface variation; growth stops at pixels above it
  float distance_tolerance = 0.01f;    ///< m; max 3D distance between 4-neighbours
  int min_size = 500;                  ///< points
  int max_size = 10000;                ///< points

  template <class V>
  void visit(V& v) {
    v("angle_threshold", angle_threshold, "rad; max angle between 4-neighbour normals (default 5 deg = 0.0873)");
    v("curvature_threshold", curvature_threshold,
      "surface variation above which a point does not grow the region (PCL RegionGrowing default 0.05)");
    v("distance_tolerance", distance_tolerance, "m; max distance between 4-neighbours of one segment (0.01 m)");
    v("min_size", min_size, "points; smaller segments are dropped (paper FEC UK value: 500, Montes et al. 2020)");
    v("max_size", max_size,
      "points; larger segments (ground) are dropped (paper FEC value: 10000, Montes et al. 2020)");
  }
};

/// The link rules of OES and ORG, defined once: the per-pair predicates below and the vectorised
/// link pass of segment_oes / segment_org (organized_clustering.cpp) both evaluate these.
/// Membership: a valid point (|z| <= FLT_MAX is isfinite, false for NaN; a form that vectorises)
/// that no barrier edge label excludes (OES) or that has a normal (ORG).
inline bool oes_member(float z, std::uint8_t edge, std::uint8_t barrier) {
  return (std::fabs(z) <= std::numeric_limits<float>::max()) & ((edge & barrier) == 0);
}
inline bool org_member(float z, float nx) {
  return (std::fabs(z) <= std::numeric_limits<float>::max()) & (std::fabs(nx) <= std::numeric_limits<float>::max());
}
/// 4-neighbours closer than the distance tolerance (`tol2` squared, m²). Symmetric exactly (squares
/// of differences of the same operands), so one evaluation serves both directions of a link.
inline bool within_tolerance(float dx, float dy, float dz, float tol2) { return dx * dx + dy * dy + dz * dz < tol2; }
/// ORG: unit normals within the angle threshold (normals face the camera: no abs).
inline bool normals_agree(float ax, float ay, float az, float bx, float by, float bz, float cos_angle) {
  return ax * bx + ay * by + az * bz > cos_angle;
}

/// OES predicate over raw arrays (cloud x/y/z and edge labels), all of width·height.
struct OesPredicate {
  const float* x;
  const float* y;
  const float* z;
  const std::uint8_t* edges;  // geometry::EdgeLabel per pixel
  std::uint8_t barrier;       // labels that exclude a pixel
  float tol2;                 // squared distance tolerance, m²

  bool member(int q) const { return oes_member(z[q], edges[q], barrier); }
  bool seed(int s) const { return member(s); }
  bool expands(int) const { return true; }
  bool similar(int p, int q) const { return within_tolerance(x[p] - x[q], y[p] - y[q], z[p] - z[q], tol2); }
};

/// ORG predicate over raw arrays (positions, unit normals, curvature), all of width·height.
struct OrgPredicate {
  const float* x;
  const float* y;
  const float* z;
  const float* nx;
  const float* ny;
  const float* nz;
  const float* curvature;
  float cos_angle;      // cos(angle_threshold)
  float max_curvature;  // curvature_threshold
  float tol2;           // squared distance tolerance, m²

  bool member(int q) const { return org_member(z[q], nx[q]); }
  bool seed(int s) const { return member(s) && expands(s); }
  bool expands(int p) const { return curvature[p] < max_curvature; }
  bool similar(int p, int q) const {
    return within_tolerance(x[p] - x[q], y[p] - y[q], z[p] - z[q], tol2) &&
           normals_agree(nx[p], ny[p], nz[p], nx[q], ny[q], nz[q], cos_angle);
  }
};

/// The flood fill's buffers plus those of the organised clusterings' own passes. Not thread-safe.
struct OrganizedClusteringWorkspace : FloodFillWorkspace {
  std::vector<std::uint8_t> links;  // per pixel link bits (3 planes: links, right, down)
  std::vector<int> runs;            // segment_oes: (first pixel, length) of each row run of members
  std::vector<int> parents;         // segment_oes: union-find parent per run, then component per run
  std::vector<int> sizes;           // segment_oes: pixels per component, then kept segment id or -1
};

/// OES segmentation. `edges` from geometry::detect_organized_edges on the same cloud.
/// segment_oes / segment_org evaluate their predicate once per 4-neighbour pair in a vectorised
/// pass (flood_fill.hpp's link bits, kept in ws.links); segment_org fills over those bits,
/// segment_oes labels their connected components by row runs and union-find (OES links are
/// symmetric and every member seeds, so a fill attempt is a component): the same segments and
/// ws.labels as flood_fill_segments with OesPredicate / OrgPredicate (tests/segmentation checks it).
/// Throws Error("oes", ...) when sizes disagree or the config is invalid.
std::vector<Segment> segment_oes(const OrganizedCloud& cloud, const std::vector<std::uint8_t>& edges,
                                 const OesConfig& cfg, OrganizedClusteringWorkspace& ws);

/// ORG segmentation; requires cloud.has_normals() (geometry::IntegralNormalEstimator).
/// Throws Error("org", ...) when normals are missing or the config is invalid.
std::vector<Segment> segment_org(const OrganizedCloud& cloud, const OrgConfig& cfg, OrganizedClusteringWorkspace& ws);

}  // namespace cropsight::segmentation
