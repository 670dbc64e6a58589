#pragma once
// Tables of rows indexed by an enum (passes, resources, shading modes): the check, for a static_assert beside
// the table, that row i describes enum value i and that there is one row per value.

#include <cstddef>

namespace curette {

template <typename Row, std::size_t N, typename Id>
constexpr bool rowsInEnumOrder(const Row (&rows)[N], Id Row::*id, Id count) {
    if (N != static_cast<std::size_t>(count)) return false;
    for (std::size_t i = 0; i < N; ++i)
        if (static_cast<std::size_t>(rows[i].*id) != i) return false;
    return true;
}

}  // namespace curette
