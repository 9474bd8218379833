// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The few CGAL names that differ between the supported releases (5.5 and 6.x),
// in one place: CGAL 6.0 renamed the AABB traits and the soup primitives with a
// `_3` suffix (the old headers warn). Elsewhere mrepair uses the forms both
// accept: an optional result (boost's in 5.5, std's in 6) is tested as a bool,
// and triangulate_hole is called with named parameters on 6, where the
// output-iterator overload is deprecated.
#ifndef MREPAIR_INTERNAL_CGAL_COMPAT_H
#define MREPAIR_INTERNAL_CGAL_COMPAT_H

#include <CGAL/version.h>

#include <CGAL/AABB_tree.h>
#if CGAL_VERSION_NR >= 1060000000
#include <CGAL/AABB_segment_primitive_3.h>
#include <CGAL/AABB_traits_3.h>
#include <CGAL/AABB_triangle_primitive_3.h>
#else
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_triangle_primitive.h>
#endif

namespace mrepair {
namespace internal {

#if CGAL_VERSION_NR >= 1060000000
template <class GeomTraits, class Primitive>
using Aabb_traits = CGAL::AABB_traits_3<GeomTraits, Primitive>;
template <class GeomTraits, class Iterator>
using Aabb_segment_primitive = CGAL::AABB_segment_primitive_3<GeomTraits, Iterator>;
template <class GeomTraits, class Iterator>
using Aabb_triangle_primitive = CGAL::AABB_triangle_primitive_3<GeomTraits, Iterator>;
#else
template <class GeomTraits, class Primitive>
using Aabb_traits = CGAL::AABB_traits<GeomTraits, Primitive>;
template <class GeomTraits, class Iterator>
using Aabb_segment_primitive = CGAL::AABB_segment_primitive<GeomTraits, Iterator>;
template <class GeomTraits, class Iterator>
using Aabb_triangle_primitive = CGAL::AABB_triangle_primitive<GeomTraits, Iterator>;
#endif

/// an AABB tree over `Primitive` with the traits of this CGAL release
template <class GeomTraits, class Primitive>
using Aabb_tree = CGAL::AABB_tree<Aabb_traits<GeomTraits, Primitive>>;

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CGAL_COMPAT_H
