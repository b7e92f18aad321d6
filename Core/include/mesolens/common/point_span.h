// SPDX-License-Identifier: GPL-3.0-or-later
// The one way Core's API takes an array of 3D points.
#pragma once

#include "mesolens/common/errors.h"

#include <array>
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

namespace mesolens {

/// A view, never an owner, of `size()` points stored as consecutive x, y, z values of type T:
/// `float` or `double`, `const` for a read-only view (`PointSpan<const double>`). Core's API
/// takes every array of points as one of these, in the units the function documents. It is
/// made from a pointer and a point count (VTK's arrays), from a flat `std::vector` of 3 values
/// per point, from a `std::vector<std::array<T, 3>>`, or from a writable span of the same type.
/// `span[i]` points at point i's x (so `span[i][2]` is its z). The viewed storage must outlive
/// the span and not be resized while it is used.
template<typename T>
class PointSpan
{
public:
  using Scalar = std::remove_const_t<T>;
  static_assert(std::is_floating_point<Scalar>::value, "points are float or double");
  static_assert(sizeof(std::array<Scalar, 3>) == 3 * sizeof(Scalar), "std::array is packed");
  /// What a span can be made from: const vectors for a read-only span (temporaries included).
  using FlatVector =
    std::conditional_t<std::is_const<T>::value, const std::vector<Scalar>, std::vector<Scalar>>;
  using ArrayVector =
    std::conditional_t<std::is_const<T>::value, const std::vector<std::array<Scalar, 3>>,
                       std::vector<std::array<Scalar, 3>>>;

  constexpr PointSpan() noexcept = default;

  /// `count` points starting at `xyz` (which may be null only when count is 0).
  constexpr PointSpan(T* xyz, std::size_t count) noexcept
    : Xyz(count > 0 ? xyz : nullptr)
    , Count(count)
  {
  }

  /// A flat array of 3 values per point. Throws InvalidInput when its length is not a multiple
  /// of 3.
  PointSpan(FlatVector& flat)
    : PointSpan(flat.data(), flat.size() / 3)
  {
    if (flat.size() % 3 != 0)
    {
      throw InvalidInput("a flat array of points must hold 3 values per point (it holds " +
                         std::to_string(flat.size()) + ")");
    }
  }

  /// An array of 3-component points.
  PointSpan(ArrayVector& points)
    : PointSpan(points.empty() ? nullptr : points.front().data(), points.size())
  {
  }

  /// A read-only view of a writable span.
  template<typename U,
           typename = std::enable_if_t<std::is_const<T>::value && std::is_same<U, Scalar>::value>>
  constexpr PointSpan(PointSpan<U> writable) noexcept
    : PointSpan(writable.data(), writable.size())
  {
  }

  /// Number of points.
  constexpr std::size_t size() const noexcept
  {
    return this->Count;
  }
  constexpr bool empty() const noexcept
  {
    return this->Count == 0;
  }
  /// The x of the first point; null when empty.
  constexpr T* data() const noexcept
  {
    return this->Xyz;
  }
  /// Number of values (3 per point).
  constexpr std::size_t value_count() const noexcept
  {
    return 3 * this->Count;
  }

  /// The x of point i (its y and z follow).
  constexpr T* operator[](std::size_t i) const noexcept
  {
    return this->Xyz + 3 * i;
  }

  /// Point i in double precision.
  std::array<double, 3> point(std::size_t i) const noexcept
  {
    const T* p = this->Xyz + 3 * i;
    return { { double(p[0]), double(p[1]), double(p[2]) } };
  }

  /// Points [first, first + count).
  constexpr PointSpan subspan(std::size_t first, std::size_t count) const noexcept
  {
    return PointSpan(this->Xyz + 3 * first, count);
  }

private:
  T* Xyz = nullptr;
  std::size_t Count = 0;
};

} // namespace mesolens
