// Quickhull in 3D (see quickhull.hpp for why and how it is checked).
#include "measure/quickhull.hpp"

#include <algorithm>
#include <cmath>

namespace cropsight::measure {

namespace {

struct Face {
  std::array<int, 3> v;   // vertices, counter-clockwise seen from outside
  std::array<int, 3> nb;  // nb[e]: face across edge e = (v[e], v[(e + 1) % 3])
  double n[3];            // unit outward normal
  double d;               // plane offset: distance(p) = n·p − d
  int outside = -1;       // head of this face's outside set (linked through `next_`)
  int far_point = -1;     // the outside point farthest above the face (the next eye)
  double far_dist = 0.0;
  int mark = 0;  // == stamp: visible from the current eye; == -stamp: tested, not visible
  bool alive = true;
};

class Builder {
 public:
  explicit Builder(const std::vector<Eigen::Vector3f>& pts) : n_(int(pts.size())), p_(3 * pts.size()) {
    double scale = 0.0;
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        p_[3 * i + std::size_t(k)] = double(pts[i][k]);
        scale = std::max(scale, std::abs(double(pts[i][k])));
      }
    eps_ = 1e-12 * std::max(scale, 1e-30);
    next_.assign(pts.size(), -1);
    faces_.reserve(2 * pts.size() + 16);  // ~2 live faces per vertex; deleted slots are reused
  }

  bool run(QuickHull& out) {
    if (n_ < 4 || !initial_simplex()) return false;
    std::vector<int> work;
    for (int f = 0; f < int(faces_.size()); ++f) work.push_back(f);
    while (!work.empty()) {
      const int f = work.back();
      work.pop_back();
      if (!faces_[std::size_t(f)].alive || faces_[std::size_t(f)].outside < 0) continue;
      if (!add_point(f)) return false;
      work.insert(work.end(), created_.begin(), created_.end());
    }
    return collect(out);
  }

 private:
  const double* pt(int i) const { return &p_[3 * std::size_t(i)]; }

  double distance(const Face& f, int i) const {
    const double* q = pt(i);
    return f.n[0] * q[0] + f.n[1] * q[1] + f.n[2] * q[2] - f.d;
  }

  // Plane of (a, b, c); false when the triangle has no area.
  bool set_plane(Face& f) const {
    const double *a = pt(f.v[0]), *b = pt(f.v[1]), *c = pt(f.v[2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0.0)) return false;
    for (int k = 0; k < 3; ++k) f.n[k] = n[k] / len;
    // offset through the centroid: the least rounding for all three vertices
    f.d = 0.0;
    for (int k = 0; k < 3; ++k) f.d += f.n[k] * (a[k] + b[k] + c[k]) / 3.0;
    return true;
  }

  bool initial_simplex() {
    // extreme points along the axes; the farthest pair spans the base edge
    int ext[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 1; i < n_; ++i)
      for (int k = 0; k < 3; ++k) {
        if (pt(i)[k] < pt(ext[2 * k])[k]) ext[2 * k] = i;
        if (pt(i)[k] > pt(ext[2 * k + 1])[k]) ext[2 * k + 1] = i;
      }
    auto sq = [&](int i, int j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += (pt(i)[k] - pt(j)[k]) * (pt(i)[k] - pt(j)[k]);
      return s;
    };
    int a = ext[0], b = ext[1];
    for (int k = 1; k < 3; ++k)
      if (sq(ext[2 * k], ext[2 * k + 1]) > sq(a, b)) a = ext[2 * k], b = ext[2 * k + 1];
    if (!(sq(a, b) > eps_ * eps_)) return false;
    // farthest from the line a-b
    const double* pa = pt(a);
    double dir[3] = {pt(b)[0] - pa[0], pt(b)[1] - pa[1], pt(b)[2] - pa[2]};
    const double dl = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (double& x : dir) x /= dl;
    int c = -1;
    double best = 0.0;
    for (int i = 0; i < n_; ++i) {
      const double q[3] = {pt(i)[0] - pa[0], pt(i)[1] - pa[1], pt(i)[2] - pa[2]};
      const double t = q[0] * dir[0] + q[1] * dir[1] + q[2] * dir[2];
      const double d2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - t * t;
      if (d2 > best) best = d2, c = i;
    }
    if (c < 0 || !(best > eps_ * eps_)) return false;
    Face base{{a, b, c}, {-1, -1, -1}, {0, 0, 0}, 0, -1, -1, 0.0, 0, true};
    if (!set_plane(base)) return false;
    int d = -1;
    best = 0.0;
    for (int i = 0; i < n_; ++i)
      if (const double s = std::abs(distance(base, i)); s > best) best = s, d = i;
    if (d < 0 || !(best > 1e3 * eps_)) return false;             // flat set
    if (distance(base, d) > 0) std::swap(base.v[1], base.v[2]);  // the apex must lie below the base
    const int A = base.v[0], B = base.v[1], C = base.v[2];
    const std::array<std::array<int, 3>, 4> tri = {{{A, B, C}, {B, A, d}, {C, B, d}, {A, C, d}}};
    for (const auto& t : tri) {
      Face f{t, {-1, -1, -1}, {0, 0, 0}, 0, -1, -1, 0.0, 0, true};
      if (!set_plane(f)) return false;
      faces_.push_back(f);
    }
    for (int f = 0; f < 4; ++f)
      for (int e = 0; e < 3; ++e) {
        const int x = faces_[std::size_t(f)].v[std::size_t(e)], y = faces_[std::size_t(f)].v[std::size_t((e + 1) % 3)];
        for (int g = 0; g < 4; ++g)
          for (int h = 0; h < 3; ++h)
            if (faces_[std::size_t(g)].v[std::size_t(h)] == y &&
                faces_[std::size_t(g)].v[std::size_t((h + 1) % 3)] == x)
              faces_[std::size_t(f)].nb[std::size_t(e)] = g;
      }
    for (const auto& f : faces_)
      for (int nb : f.nb)
        if (nb < 0) return false;
    // outside sets: each point goes to the first face it lies above
    for (int i = 0; i < n_; ++i) {
      if (i == A || i == B || i == C || i == d) continue;
      for (int f = 0; f < 4; ++f)
        if (const double s = distance(faces_[std::size_t(f)], i); s > eps_) {
          push_outside(faces_[std::size_t(f)], i, s);
          break;
        }
    }
    return true;
  }

  void push_outside(Face& f, int i, double dist) {
    next_[std::size_t(i)] = f.outside;
    f.outside = i;
    if (dist > f.far_dist) f.far_dist = dist, f.far_point = i;
  }

  int edge_to(const Face& f, int g) const {
    for (int e = 0; e < 3; ++e)
      if (f.nb[std::size_t(e)] == g) return e;
    return -1;
  }

  // Depth-first walk over the faces visible from `eye`, starting at face f entered through edge
  // `e_in` (-1: the first face). Horizon edges come out in counter-clockwise cyclic order.
  bool walk(int f, int e_in, int eye) {
    faces_[std::size_t(f)].mark = stamp_;
    visible_.push_back(f);
    const int start = e_in < 0 ? 0 : e_in + 1, count = e_in < 0 ? 3 : 2;
    for (int k = 0; k < count; ++k) {
      const int e = (start + k) % 3;
      const int g = faces_[std::size_t(f)].nb[std::size_t(e)];
      Face& fg = faces_[std::size_t(g)];
      if (fg.mark == stamp_) continue;
      if (fg.mark != -stamp_ && distance(fg, eye) > eps_) {
        const int eg = edge_to(fg, f);
        if (eg < 0 || !walk(g, eg, eye)) return false;
      } else {
        fg.mark = -stamp_;
        horizon_.push_back({f, e});
      }
    }
    return true;
  }

  bool add_point(int f0) {
    const int eye = faces_[std::size_t(f0)].far_point;  // the farthest point of f0's outside set
    ++stamp_;
    visible_.clear();
    horizon_.clear();
    if (!walk(f0, -1, eye) || horizon_.size() < 3) return false;
    // the horizon must be one closed chain
    const std::size_t h = horizon_.size();
    auto from = [&](std::size_t j) { return faces_[std::size_t(horizon_[j][0])].v[std::size_t(horizon_[j][1])]; };
    auto to = [&](std::size_t j) {
      return faces_[std::size_t(horizon_[j][0])].v[std::size_t((horizon_[j][1] + 1) % 3)];
    };
    for (std::size_t j = 0; j < h; ++j)
      if (to(j) != from((j + 1) % h)) return false;

    // New faces reuse the slots of faces deleted before (a small working set stays in cache).
    created_.clear();
    for (std::size_t j = 0; j < h; ++j) {
      const int f = horizon_[j][0], e = horizon_[j][1];
      const int g = faces_[std::size_t(f)].nb[std::size_t(e)];
      Face nf{{from(j), to(j), eye}, {g, -1, -1}, {0, 0, 0}, 0, -1, -1, 0.0, 0, true};
      if (!set_plane(nf)) return false;
      const int eg = edge_to(faces_[std::size_t(g)], f);
      if (eg < 0) return false;
      int slot;
      if (!free_.empty()) {
        slot = free_.back();
        free_.pop_back();
        faces_[std::size_t(slot)] = nf;
      } else {
        slot = int(faces_.size());
        faces_.push_back(nf);
      }
      faces_[std::size_t(g)].nb[std::size_t(eg)] = slot;
      created_.push_back(slot);
    }
    for (std::size_t j = 0; j < h; ++j) {
      const int f = created_[j], fnext = created_[(j + 1) % h];
      faces_[std::size_t(f)].nb[1] = fnext;
      faces_[std::size_t(fnext)].nb[2] = f;
    }
    // the visible faces' outside points go to the first new face they lie above, or are inside
    for (int f : visible_) {
      Face& vf = faces_[std::size_t(f)];
      vf.alive = false;
      for (int i = vf.outside; i >= 0;) {
        const int nxt = next_[std::size_t(i)];
        if (i != eye)
          for (int g : created_)
            if (const double s = distance(faces_[std::size_t(g)], i); s > eps_) {
              push_outside(faces_[std::size_t(g)], i, s);
              break;
            }
        i = nxt;
      }
      vf.outside = -1;
      free_.push_back(f);
    }
    return true;
  }

  bool collect(QuickHull& out) const {
    out.vertices.clear();
    out.triangles.clear();
    // incident live faces per corner, as one flat array (no allocation per corner)
    std::vector<int> start(std::size_t(n_) + 1, 0), around;
    int live = 0;
    for (const Face& face : faces_) {
      if (!face.alive) continue;
      ++live;
      for (int v : face.v) ++start[std::size_t(v) + 1];
      for (int g : face.nb)
        if (!faces_[std::size_t(g)].alive) return false;  // a live face next to a deleted one
    }
    for (int i = 0; i < n_; ++i) start[std::size_t(i) + 1] += start[std::size_t(i)];
    around.resize(std::size_t(3 * live));
    std::vector<int> fill(start.begin(), start.end() - 1);
    out.triangles.reserve(std::size_t(live));
    for (int f = 0; f < int(faces_.size()); ++f) {
      const Face& face = faces_[std::size_t(f)];
      if (!face.alive) continue;
      out.triangles.push_back(face.v);
      for (int v : face.v) around[std::size_t(fill[std::size_t(v)]++)] = f;
    }
    int corners = 0;
    for (int i = 0; i < n_; ++i) {
      const int b = start[std::size_t(i)], e = start[std::size_t(i) + 1];
      if (b == e) continue;
      ++corners;
      if (strict_vertex(i, &around[std::size_t(b)], e - b)) out.vertices.push_back(i);
    }
    // a closed triangulated sphere: V − E + F = 2 with E = 3F/2
    return 2 * corners == live + 4 && out.vertices.size() >= 4;
  }

  // A triangulation corner that ended up inside a flat facet or on a straight edge of the hull
  // (exactly coplanar / collinear input: later points landed in the same plane) is not a vertex
  // of the hull; qhull merges such facets away, so it is dropped here too. Fast path: the normals
  // of the incident faces span 3D (a true cone apex). Otherwise, inside a facet: every incident
  // triangle lies in one plane; on an edge: two neighbours lie on opposite sides of it on one line.
  bool strict_vertex(int v, const int* faces, int count) const {
    const double* n0 = faces_[std::size_t(faces[0])].n;
    int far = 0;
    double lowest = 2.0;
    for (int k = 1; k < count; ++k) {
      const double* n = faces_[std::size_t(faces[k])].n;
      if (const double c = n0[0] * n[0] + n0[1] * n[1] + n0[2] * n[2]; c < lowest) lowest = c, far = k;
    }
    const double* n1 = faces_[std::size_t(faces[far])].n;
    const double c[3] = {n0[1] * n1[2] - n0[2] * n1[1], n0[2] * n1[0] - n0[0] * n1[2], n0[0] * n1[1] - n0[1] * n1[0]};
    for (int k = 1; k < count; ++k) {
      const double* n = faces_[std::size_t(faces[k])].n;
      if (std::abs(c[0] * n[0] + c[1] * n[1] + c[2] * n[2]) > 1e-6) return true;
    }
    // Slow path (normals nearly in one plane: flat, an edge, or a vertex pushed out by rounding).
    const Face& f0 = faces_[std::size_t(faces[0])];
    bool flat = true;
    for (int k = 0; k < count; ++k)
      for (int w : faces_[std::size_t(faces[k])].v)
        if (std::abs(distance(f0, w)) > eps_) flat = false;
    if (flat) return false;
    std::vector<int> link;
    for (int k = 0; k < count; ++k)
      for (int w : faces_[std::size_t(faces[k])].v)
        if (w != v && std::find(link.begin(), link.end(), w) == link.end()) link.push_back(w);
    const double* pv = pt(v);
    for (std::size_t a = 0; a < link.size(); ++a)
      for (std::size_t b = a + 1; b < link.size(); ++b) {
        const double *pa = pt(link[a]), *pb = pt(link[b]);
        const double x[3] = {pa[0] - pv[0], pa[1] - pv[1], pa[2] - pv[2]};
        const double y[3] = {pb[0] - pv[0], pb[1] - pv[1], pb[2] - pv[2]};
        const double dot = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
        if (dot >= 0) continue;  // same side of v
        const double cr[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
        const double cross = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
        const double ly = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
        if (cross <= eps_ * ly) return false;  // v within eps of the line through a and b, between them
      }
    return true;
  }

  int n_;
  std::vector<double> p_;
  std::vector<int> next_;
  std::vector<Face> faces_;
  std::vector<int> visible_, created_, free_;
  std::vector<std::array<int, 2>> horizon_;
  double eps_ = 0.0;
  int stamp_ = 0;
};

}  // namespace

bool quickhull(const std::vector<Eigen::Vector3f>& points, QuickHull& out) {
  Builder b(points);
  return b.run(out);
}

}  // namespace cropsight::measure
