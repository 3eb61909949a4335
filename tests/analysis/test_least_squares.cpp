// the shared Levenberg–Marquardt minimiser: exact recovery, the covariance against a linear
// problem's exact one, and a domain the steps must stay in
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/least_squares.hpp"

namespace gs {
namespace {

// y = A exp(−k x) sampled at x = 0…19, σ = 0.01 everywhere
Residuals decay(const Eigen::VectorXd& y) {
  return [y](const Eigen::VectorXd& p, Eigen::VectorXd& r, Eigen::MatrixXd* jac) {
    r.resize(y.size());
    if (jac) jac->resize(y.size(), 2);
    for (Eigen::Index i = 0; i < y.size(); ++i) {
      const double x = static_cast<double>(i), e = std::exp(-p(1) * x);
      r(i) = (y(i) - p(0) * e) / 0.01;
      if (jac) {
        (*jac)(i, 0) = -e / 0.01;
        (*jac)(i, 1) = p(0) * x * e / 0.01;
      }
    }
    return r.squaredNorm();
  };
}

TEST(LeastSquares, RecoversAnExponentialExactly) {
  Eigen::VectorXd y(20);
  for (Eigen::Index i = 0; i < 20; ++i) y(i) = 2.5 * std::exp(-0.3 * static_cast<double>(i));
  const LmOutcome o = levenberg_marquardt(decay(y), Eigen::Vector2d(1.0, 1.0));
  EXPECT_TRUE(o.converged);
  EXPECT_NEAR(o.p(0), 2.5, 1e-9);
  EXPECT_NEAR(o.p(1), 0.3, 1e-9);
  EXPECT_LT(o.chi2, 1e-12);
}

TEST(LeastSquares, LinearProblemGivesTheExactCovariance) {
  // y = a + b x: one Gauss–Newton step is exact, and (JᵀJ)⁻¹ is the textbook covariance
  const int n = 11;
  const Residuals line = [n](const Eigen::VectorXd& p, Eigen::VectorXd& r, Eigen::MatrixXd* jac) {
    r.resize(n);
    if (jac) jac->resize(n, 2);
    for (int i = 0; i < n; ++i) {
      const double x = i, y = 1.0 + 2.0 * x + (i % 2 ? 0.1 : -0.1);
      r(i) = (y - p(0) - p(1) * x) / 0.1;
      if (jac) {
        (*jac)(i, 0) = -1.0 / 0.1;
        (*jac)(i, 1) = -x / 0.1;
      }
    }
    return r.squaredNorm();
  };
  const LmOutcome o = levenberg_marquardt(line, Eigen::Vector2d(0.0, 0.0));
  const Eigen::Matrix2d cov = (o.jac.transpose() * o.jac).inverse();
  // Σx = 55, Σx² = 385, n = 11: var(b) = σ²·n/(nΣx² − (Σx)²) = 0.01·11/1210
  EXPECT_NEAR(cov(1, 1), 0.01 * 11.0 / 1210.0, 1e-12);
  EXPECT_NEAR(cov(0, 0), 0.01 * 385.0 / 1210.0, 1e-12);
}

TEST(LeastSquares, StepsStayInTheDomain) {
  // the unconstrained minimum of (p − (−1))² lies outside p > 0: the fit stops at the edge
  const Residuals r = [](const Eigen::VectorXd& p, Eigen::VectorXd& res, Eigen::MatrixXd* jac) {
    if (!(p(0) > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    res.resize(1);
    res(0) = p(0) + 1.0;
    if (jac) jac->setConstant(1, 1, 1.0);
    return res.squaredNorm();
  };
  const LmOutcome o = levenberg_marquardt(r, Eigen::VectorXd::Constant(1, 3.0));
  EXPECT_GT(o.p(0), 0.0);
  EXPECT_LT(o.p(0), 1e-3);
  EXPECT_TRUE(o.converged);
}

}  // namespace
}  // namespace gs
