// Second-order forward-mode differentiation for the collocation Hessian: a
// value, its gradient and its Hessian (lower triangle, packed) in N
// variables. Nesting Eigen's AutoDiffScalar gives the same numbers but keeps
// the full N x N square and builds expression temporaries at every step: on
// the 16-state flight model it was 60% of a solve; this type needs about a
// quarter of the arithmetic and none of the temporaries.
#ifndef HYLO_TRAINER_HYPERDUAL_HPP
#define HYLO_TRAINER_HYPERDUAL_HPP

#include <cmath>

namespace hylo::trainer {

template <int N>
struct Hyper {
	static constexpr int NH = N * (N + 1) / 2;   // packed lower triangle, row by row
	double v = 0;
	double g[N] = {};
	double h[NH] = {};

	Hyper() = default;
	Hyper(double value) : v(value) {}   // NOLINT: a constant, as a double converts
	// The independent variable `index` at `value`.
	static Hyper variable(double value, int index)
	{
		Hyper r(value);
		r.g[index] = 1;
		return r;
	}
	// d2/(dx_i dx_j), any order of i and j.
	double hess(int i, int j) const { return i >= j ? h[i * (i + 1) / 2 + j] : h[j * (j + 1) / 2 + i]; }
};

namespace internal {
// r = f(a) by the chain rule, with f' = d1 and f'' = d2 at a.v.
template <int N>
Hyper<N> chain(const Hyper<N> &a, double f, double d1, double d2)
{
	Hyper<N> r(f);
	for (int i = 0; i < N; i++)
		r.g[i] = d1 * a.g[i];
	int e = 0;
	for (int i = 0; i < N; i++)
		for (int j = 0; j <= i; j++, e++)
			r.h[e] = d1 * a.h[e] + d2 * a.g[i] * a.g[j];
	return r;
}
}  // namespace internal

template <int N>
Hyper<N> operator+(const Hyper<N> &a, const Hyper<N> &b)
{
	Hyper<N> r(a.v + b.v);
	for (int i = 0; i < N; i++)
		r.g[i] = a.g[i] + b.g[i];
	for (int e = 0; e < Hyper<N>::NH; e++)
		r.h[e] = a.h[e] + b.h[e];
	return r;
}

template <int N>
Hyper<N> operator-(const Hyper<N> &a)
{
	Hyper<N> r(-a.v);
	for (int i = 0; i < N; i++)
		r.g[i] = -a.g[i];
	for (int e = 0; e < Hyper<N>::NH; e++)
		r.h[e] = -a.h[e];
	return r;
}

template <int N>
Hyper<N> operator-(const Hyper<N> &a, const Hyper<N> &b)
{
	Hyper<N> r(a.v - b.v);
	for (int i = 0; i < N; i++)
		r.g[i] = a.g[i] - b.g[i];
	for (int e = 0; e < Hyper<N>::NH; e++)
		r.h[e] = a.h[e] - b.h[e];
	return r;
}

template <int N>
Hyper<N> operator*(const Hyper<N> &a, const Hyper<N> &b)
{
	Hyper<N> r(a.v * b.v);
	for (int i = 0; i < N; i++)
		r.g[i] = a.v * b.g[i] + b.v * a.g[i];
	int e = 0;
	for (int i = 0; i < N; i++)
		for (int j = 0; j <= i; j++, e++)
			r.h[e] = a.v * b.h[e] + b.v * a.h[e] + a.g[i] * b.g[j] + a.g[j] * b.g[i];
	return r;
}

template <int N>
Hyper<N> operator*(double c, const Hyper<N> &a)
{
	Hyper<N> r(c * a.v);
	for (int i = 0; i < N; i++)
		r.g[i] = c * a.g[i];
	for (int e = 0; e < Hyper<N>::NH; e++)
		r.h[e] = c * a.h[e];
	return r;
}

template <int N>
Hyper<N> operator*(const Hyper<N> &a, double c) { return c * a; }

template <int N>
Hyper<N> operator+(const Hyper<N> &a, double c)
{
	Hyper<N> r = a;
	r.v += c;
	return r;
}

template <int N>
Hyper<N> operator+(double c, const Hyper<N> &a) { return a + c; }

template <int N>
Hyper<N> operator-(const Hyper<N> &a, double c) { return a + (-c); }

template <int N>
Hyper<N> operator-(double c, const Hyper<N> &a) { return (-a) + c; }

template <int N>
Hyper<N> operator/(const Hyper<N> &a, double c) { return (1.0 / c) * a; }

template <int N>
Hyper<N> operator/(const Hyper<N> &a, const Hyper<N> &b)
{
	double ib = 1.0 / b.v;
	return a * internal::chain(b, ib, -ib * ib, 2 * ib * ib * ib);
}

template <int N>
Hyper<N> operator/(double c, const Hyper<N> &b) { return c * (Hyper<N>(1.0) / b); }

template <int N>
Hyper<N> sin(const Hyper<N> &a)
{
	double s = std::sin(a.v), c = std::cos(a.v);
	return internal::chain(a, s, c, -s);
}

template <int N>
Hyper<N> cos(const Hyper<N> &a)
{
	double s = std::sin(a.v), c = std::cos(a.v);
	return internal::chain(a, c, -s, -c);
}

template <int N>
Hyper<N> tan(const Hyper<N> &a)
{
	double t = std::tan(a.v), d1 = 1 + t * t;
	return internal::chain(a, t, d1, 2 * t * d1);
}

template <int N>
Hyper<N> tanh(const Hyper<N> &a)
{
	double t = std::tanh(a.v), d1 = 1 - t * t;
	return internal::chain(a, t, d1, -2 * t * d1);
}

template <int N>
Hyper<N> sqrt(const Hyper<N> &a)
{
	double s = std::sqrt(a.v);
	return internal::chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}

}  // namespace hylo::trainer

#endif
