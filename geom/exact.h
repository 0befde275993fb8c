// The kernel and its basic types, named once. Included only by geom/*.cpp.
//
// Exacity is built on the exact kernel. The robustness benchmark (benchmarks/robustness.cpp)
// builds the very same code on floating-point kernels instead, chosen here at compile time
// by EXACITY_FLOAT_KERNEL: 1 Epick, 2 plain doubles (Simple_cartesian<double>), nothing else
// changed. 3 is the practitioner's float build: Epick, every constructed point snapped to a
// fixed grid (`constructed`), equality of constructed points tested on it, every batch noded
// by iterated snap rounding in doubles before the arrangement sees it (geom/snap_noding.h;
// docs/design.md, Exactness). 4 is 3 on plain doubles, whose predicates round too. 5, the grid
// build (geom/grid_kernel.h), is 4 as a practitioner would write it: a decimal 1e-6 m grid
// whose points are not exact doubles, and each batch snap-rounded in one pass, not iterated.
// Lines here keep their places so that the other kernels' objects stay in ccache.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include <CGAL/Interval_nt.h>

#include "geom/plain.h"

#if !defined(EXACITY_FLOAT_KERNEL)
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#elif EXACITY_FLOAT_KERNEL == 1
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#elif EXACITY_FLOAT_KERNEL == 2
#include <CGAL/Simple_cartesian.h>
#elif EXACITY_FLOAT_KERNEL == 3
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include "geom/snap_noding.h"
#elif EXACITY_FLOAT_KERNEL == 4
#include <CGAL/Simple_cartesian.h>
#include "geom/snap_noding.h"
#elif EXACITY_FLOAT_KERNEL == 5
#include "geom/grid_kernel.h"  // its kernel, name and grid
#else
#error "EXACITY_FLOAT_KERNEL: 1 (Epick), 2 (Simple_cartesian), 3 and 4 (the same, snapped) or 5 (the grid build)"
#endif
#if EXACITY_FLOAT_KERNEL == 3 || EXACITY_FLOAT_KERNEL == 4 || EXACITY_FLOAT_KERNEL == 5
#define EXACITY_SNAPPED_KERNEL 1  // the snapped builds share every line of their snapping
#endif

namespace geom::exact {

#if !defined(EXACITY_FLOAT_KERNEL)
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
inline constexpr const char* kKernelName = "exact (Epeck)";
#elif EXACITY_FLOAT_KERNEL == 1
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
inline constexpr const char* kKernelName = "float (Epick)";
#elif EXACITY_FLOAT_KERNEL == 2
using Kernel = CGAL::Simple_cartesian<double>;
inline constexpr const char* kKernelName = "float (Simple_cartesian<double>)";
#elif EXACITY_FLOAT_KERNEL == 3
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
inline constexpr const char* kKernelName = "float snapped (Epick, constructions on a 2^-24 m grid)";
#elif EXACITY_FLOAT_KERNEL == 4  // 5: geom/grid_kernel.h
using Kernel = CGAL::Simple_cartesian<double>;
inline constexpr const char* kKernelName = "float snapped (Simple_cartesian<double>, constructions on a 2^-24 m grid)";
#endif

#if defined(EXACITY_SNAPPED_KERNEL)
inline constexpr bool kSnapped = true;
#else
inline constexpr bool kSnapped = false;
#endif
#if !defined(EXACITY_SNAP_STEP)            // the snapped builds' grid (the grid build's: geom/grid_kernel.h): 2^-24 m,
#define EXACITY_SNAP_STEP 1.0 / (1 << 24)  // 60 nm, a power of two so every point of geom/grid.h's grid is on it
#endif  // and fine enough that a snapped point stays within the validator's 1 µm of the edge it was computed on
inline constexpr double kSnapStep = EXACITY_SNAP_STEP;
using FT = Kernel::FT;
using Point = Kernel::Point_2;
using Segment = Kernel::Segment_2;
using Line = Kernel::Line_2;

inline Point to_exact(Vec2 p) {
  CGAL_assertion(std::isfinite(p.x) && std::isfinite(p.y));
  return Point(p.x, p.y);
}

// A point this code constructed (a meeting of two lines, a projection): itself, or in the
// snapped build the nearest point of its grid, where equality tests then find it again.
inline Point constructed(const Point& p) {
#if defined(EXACITY_SNAPPED_KERNEL)
  const Vec2 s = snap_to({p.x(), p.y()}, kSnapStep);
  return Point(s.x, s.y);
#else
  return p;
#endif
}

// The nearest double, ties to even: what snap rounding's pixels assume. (CGAL::to_double
// truncates GMP's rationals towards zero; to_interval gives the two doubles around.)
template <typename Exact>
double nearest_double_by_halfway(const Exact& v) {
  const auto [below, above] = CGAL::to_interval(v);
  if (below == above) return below;
  const Exact halfway = (Exact(below) + Exact(above)) / 2;
  if (v < halfway) return below;
  if (halfway < v) return above;
  return (std::bit_cast<std::uint64_t>(below) & 1) == 0 ? below : above;
}
template <typename Exact>
double nearest_double(const Exact& v) {
#if !defined(EXACITY_FLOAT_KERNEL) && defined(CGAL_USE_GMPXX)
  // A GMP rational: MPFR rounds it once to 53 bits, ties to even, subnormals as doubles
  // have them (to_interval's way, rounding to nearest): the halfway rational's arithmetic
  // was most of the cost of rounding a cell's vertices (PlanarMap::cells).
  if constexpr (std::is_same_v<Exact, mpq_class>) {
    const mpfr_exp_t emin = mpfr_get_emin();
    mpfr_set_emin(-1073);
    MPFR_DECL_INIT(y, 53);
    const int inexact = mpfr_set_q(y, v.get_mpq_t(), MPFR_RNDN);
    mpfr_subnormalize(y, inexact, MPFR_RNDN);
    const double nearest = mpfr_get_d(y, MPFR_RNDN);  // exact, unless past the doubles' range
    mpfr_set_emin(emin);
    if (std::isfinite(nearest)) return nearest;
  }
#endif
  return nearest_double_by_halfway(v);
}

// Zero as +0: an exact zero has no sign, but an interval's bound may be -0 (a point made
// from -0.0, or from text that says so), and -0 is written "-0" (%a: "-0x0p+0"), so the
// bytes would follow how the point was made rather than its value.
inline double unsigned_zero(double v) { return v == 0 ? 0.0 : v; }

// Rounds the exact value to the nearest doubles, so the result does not depend on how far
// the lazy kernel happened to evaluate it, nor on how the point was made (zero is +0). A
// point whose interval is a single double is that double; any other is evaluated exactly
// once, as a point (p.x() would add a lazy node each call).
inline Vec2 to_plain(const Point& p) {
#if !defined(EXACITY_FLOAT_KERNEL)
  const auto& a = p.approx();
  if (a.x().inf() == a.x().sup() && a.y().inf() == a.y().sup())
    return {unsigned_zero(a.x().inf()), unsigned_zero(a.y().inf())};
  const auto& e = CGAL::exact(p);
  return {nearest_double(e.x()), nearest_double(e.y())};
#else
  return {unsigned_zero(p.x()), unsigned_zero(p.y())};
#endif
}

// Intervals that hold the point's coordinates, known without evaluating it exactly.
inline std::array<CGAL::Interval_nt<false>, 2> approx(const Point& p) {
#if !defined(EXACITY_FLOAT_KERNEL)
  const auto& a = p.approx();
  return {a.x(), a.y()};
#else
  return {CGAL::Interval_nt<false>(p.x()), CGAL::Interval_nt<false>(p.y())};
#endif
}

// A ring of exact points (not closed: the last point is not repeated).
using ExactRing = std::vector<Point>;

// The ring with its vertices rounded to doubles. Exact vertices closer than the rounding
// step can land on one double: repeats and the zero-width spikes they leave are dropped.
// Rings that share exact vertices drop them alike, so written polygons still meet edge to
// edge. Empty when the ring collapses.
Ring round_ring(const std::vector<Point>& points);

// Pieces whose union is the stroke of a polyline (see PlanarMap::add_stroke), each a
// counter-clockwise simple ring.
std::vector<ExactRing> stroke_pieces(const Polyline& line, double half_width);

// What fills the outer side of the bend a -> q -> b in a stroke: a mitre, or a bevel past
// the mitre limit; empty where the path runs straight on.
ExactRing joint_piece(Vec2 a, Vec2 q, Vec2 b, double half_width);

// A 16-gon around the disc of radius r at c, its corners on the grid.
ExactRing disc_piece(Vec2 c, double r);

// The mitred junction of streets meeting at q (docs/design.md, Algorithms: street-graph layout): each street
// leaves q towards `toward` with its half width. Around q, each pair of neighbouring
// streets meets where their sides cross (a bevel where that mitre reaches past the mitre
// limit on the outside of a bend), and each street is cut straight across where its last
// corner lies, so the junction is one star-shaped ring whose sides lie on the streets'
// stroke sides. Empty where no junction is needed (two streets running straight on) or
// none can be drawn (two streets leaving q so close in angle that their sides part only
// past their length): the caller falls back to a disc.
ExactRing junction_piece(Vec2 q, const std::vector<JunctionArm>& arms);

}  // namespace geom::exact
