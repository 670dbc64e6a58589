#pragma once
// The outline of a binary slice as closed polygons along pixel edges: the RT Structure Set's representation
// of a region (CLOSED_PLANAR contours, PS3.3 C.8.8.6) made from a label map without changing it. Pixel (i, j)
// is the square [i - 0.5, i + 0.5] x [j - 0.5, j + 0.5] in index space; the polygons are the boundary of the
// union of the set pixels, so a point-in-polygon test at pixel centres (even-odd over a slice's polygons, as
// RT planning systems and plastimatch rasterise) gives back exactly the set pixels, and each slice's
// polygons enclose exactly its pixel area (outer boundaries counter-clockwise in (i, j), holes clockwise).
// Where two set pixels meet only at a corner, the boundary turns towards the set pixels (they are separate
// polygons that touch at that corner, never crossing). Collinear vertices are dropped.

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace curette::io {

// `mask` is width x height bytes, i fastest; non-zero is set. Vertices are pixel corners in index space
// (half-integers).
std::vector<std::vector<glm::dvec2>> sliceOutlines(const std::uint8_t* mask, int width, int height);

// The signed area of a polygon (shoelace formula): positive when counter-clockwise.
double polygonArea(const std::vector<glm::dvec2>& polygon);

}  // namespace curette::io
