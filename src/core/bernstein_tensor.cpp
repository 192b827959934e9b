#include "volspline/core/bernstein_tensor.h"

#include <algorithm>
#include <cmath>

#include "volspline/core/error.h"

namespace volspline {

namespace {

// The lines of `direction`: `count` lines of `length` numbers `stride` apart, line l starting at
// offsets[l].
struct Lines {
  int length = 0;
  std::size_t stride = 1;
  std::vector<std::size_t> offsets;
};

Lines lines_of(const std::array<int, 3>& degrees, int direction) {
  const std::array<int, 3> n{degrees[0] + 1, degrees[1] + 1, degrees[2] + 1};
  Lines lines;
  lines.length = n[static_cast<std::size_t>(direction)];
  const std::array<std::size_t, 3> strides{1, static_cast<std::size_t>(n[0]), static_cast<std::size_t>(n[0] * n[1])};
  lines.stride = strides[static_cast<std::size_t>(direction)];
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        const std::array<int, 3> idx{i, j, k};
        if (idx[static_cast<std::size_t>(direction)] != 0) continue;
        lines.offsets.push_back(static_cast<std::size_t>(i) + strides[1] * static_cast<std::size_t>(j) +
                                strides[2] * static_cast<std::size_t>(k));
      }
    }
  }
  return lines;
}

void check_direction(int direction) {
  if (direction < 0 || direction > 2) throw InvalidInput("direction must be 0, 1 or 2, got " + std::to_string(direction));
}


}  // namespace

double binomial_coefficient(int n, int k) {
  if (k < 0 || k > n) return 0.0;
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

BernsteinTensor::BernsteinTensor(std::array<int, 3> d) : degrees(d) {
  for (int x : d) {
    if (x < 0) throw InvalidInput("Bernstein degrees must be >= 0");
  }
  coefficients.assign(static_cast<std::size_t>((d[0] + 1) * (d[1] + 1) * (d[2] + 1)), 0.0);
}

double bernstein_evaluate(const BernsteinTensor& f, const std::array<double, 3>& s) {
  std::vector<double> work = f.coefficients;
  std::array<int, 3> n{f.size(0), f.size(1), f.size(2)};
  // Collapse direction 0, then 1, then 2; after each step the data is contiguous again.
  for (int d = 0; d < 3; ++d) {
    const int len = n[static_cast<std::size_t>(d)];
    const double t = s[static_cast<std::size_t>(d)], t1 = 1 - t;
    std::size_t outer = 1;
    for (int e = d + 1; e < 3; ++e) outer *= static_cast<std::size_t>(n[static_cast<std::size_t>(e)]);
    for (std::size_t o = 0; o < outer; ++o) {
      double* line = work.data() + o * static_cast<std::size_t>(len);
      for (int r = 1; r < len; ++r) {
        for (int i = 0; i + r < len; ++i) line[i] = t1 * line[i] + t * line[i + 1];
      }
      work[o] = line[0];
    }
    n[static_cast<std::size_t>(d)] = 1;
  }
  return work[0];
}

std::pair<BernsteinTensor, BernsteinTensor> bernstein_split(const BernsteinTensor& f, int direction, double t) {
  check_direction(direction);
  BernsteinTensor left = f, right = f;
  const Lines lines = lines_of(f.degrees, direction);
  const int len = lines.length;
  const double t1 = 1 - t;
  double buffer[64];
  std::vector<double> big;
  double* w = buffer;
  if (len > 64) {
    big.resize(static_cast<std::size_t>(len));
    w = big.data();
  }
  for (std::size_t offset : lines.offsets) {
    for (int i = 0; i < len; ++i) w[i] = f.coefficients[offset + lines.stride * static_cast<std::size_t>(i)];
    left.coefficients[offset] = w[0];
    right.coefficients[offset + lines.stride * static_cast<std::size_t>(len - 1)] = w[len - 1];
    for (int r = 1; r < len; ++r) {
      for (int i = 0; i + r < len; ++i) w[i] = t1 * w[i] + t * w[i + 1];
      left.coefficients[offset + lines.stride * static_cast<std::size_t>(r)] = w[0];
      right.coefficients[offset + lines.stride * static_cast<std::size_t>(len - 1 - r)] = w[len - 1 - r];
    }
  }
  return {std::move(left), std::move(right)};
}

std::pair<double, double> bernstein_coefficient_range(const BernsteinTensor& f) {
  const auto [lo, hi] = std::minmax_element(f.coefficients.begin(), f.coefficients.end());
  return {*lo, *hi};
}

double bernstein_max_abs(const BernsteinTensor& f) {
  double m = 0;
  for (double c : f.coefficients) m = std::max(m, std::abs(c));
  return m;
}

BernsteinTensor bernstein_derivative(const BernsteinTensor& f, int direction) {
  check_direction(direction);
  const int n = f.degrees[static_cast<std::size_t>(direction)];
  if (n == 0) return BernsteinTensor({0, 0, 0});
  std::array<int, 3> d = f.degrees;
  d[static_cast<std::size_t>(direction)] = n - 1;
  BernsteinTensor g(d);
  for (int k = 0; k < g.size(2); ++k) {
    for (int j = 0; j < g.size(1); ++j) {
      for (int i = 0; i < g.size(0); ++i) {
        const std::array<int, 3> a{i, j, k};
        std::array<int, 3> b = a;
        b[static_cast<std::size_t>(direction)] += 1;
        g.at(i, j, k) = n * (f.at(b[0], b[1], b[2]) - f.at(a[0], a[1], a[2]));
      }
    }
  }
  return g;
}

BernsteinTensor bernstein_product(const BernsteinTensor& f, const BernsteinTensor& g) {
  const std::array<int, 3> d{f.degrees[0] + g.degrees[0], f.degrees[1] + g.degrees[1], f.degrees[2] + g.degrees[2]};
  BernsteinTensor h(d);
  auto scale = [](const std::array<int, 3>& deg, int i, int j, int k) {
    return binomial_coefficient(deg[0], i) * binomial_coefficient(deg[1], j) * binomial_coefficient(deg[2], k);
  };
  for (int k = 0; k < f.size(2); ++k)
    for (int j = 0; j < f.size(1); ++j)
      for (int i = 0; i < f.size(0); ++i) {
        const double a = f.at(i, j, k) * scale(f.degrees, i, j, k);
        for (int kk = 0; kk < g.size(2); ++kk)
          for (int jj = 0; jj < g.size(1); ++jj)
            for (int ii = 0; ii < g.size(0); ++ii) h.at(i + ii, j + jj, k + kk) += a * g.at(ii, jj, kk) * scale(g.degrees, ii, jj, kk);
      }
  for (int k = 0; k < h.size(2); ++k)
    for (int j = 0; j < h.size(1); ++j)
      for (int i = 0; i < h.size(0); ++i) h.at(i, j, k) /= scale(d, i, j, k);
  return h;
}

BernsteinTensor bernstein_elevate(const BernsteinTensor& f, std::array<int, 3> degrees) {
  for (int d = 0; d < 3; ++d) {
    if (degrees[static_cast<std::size_t>(d)] < f.degrees[static_cast<std::size_t>(d)]) {
      throw InvalidInput("degree elevation cannot lower a degree");
    }
  }
  // Multiplying by the constant 1 written in degree (r - n) raises the degree exactly.
  BernsteinTensor one({degrees[0] - f.degrees[0], degrees[1] - f.degrees[1], degrees[2] - f.degrees[2]});
  std::fill(one.coefficients.begin(), one.coefficients.end(), 1.0);
  return bernstein_product(f, one);
}

}  // namespace volspline
