#pragma once
#include <cstddef>

namespace dwt {

// A view of a 2-D sample plane that owns nothing: rows of `width` samples, `stride` samples apart.
template <class T>
struct PlaneSpan {
  T* data = nullptr;
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;  // in samples, >= width

  T* row(int y) const { return data + static_cast<std::ptrdiff_t>(y) * stride; }
  T& at(int x, int y) const { return row(y)[x]; }
};

template <class T>
PlaneSpan<T> make_span(T* data, int width, int height) {
  return PlaneSpan<T>{data, width, height, width};
}

}  // namespace dwt
