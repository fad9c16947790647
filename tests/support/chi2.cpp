#include "support/chi2.h"

#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace rr::test {

std::string Chi2Outcome::describe() const {
    std::ostringstream s;
    if (!failure.empty()) return failure;
    s << "chi2 = " << statistic << ", dof = " << degreesOfFreedom << ", p = " << pValue << " ("
      << pooledCells << " cells pooled)";
    return s.str();
}

Chi2Outcome chi2GoodnessOfFit(const std::vector<double>& observed,
                              const std::vector<double>& expected, double minExpected) {
    Chi2Outcome out;
    double pooledObserved = 0, pooledExpected = 0;
    int cells = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] <= 0 && observed[i] > 0) {
            std::ostringstream s;
            s << observed[i] << " samples in cell " << i << " where the density is zero";
            out.failure = s.str();
            out.pValue = 0;
            return out;
        }
        if (expected[i] < minExpected) {
            pooledObserved += observed[i];
            pooledExpected += expected[i];
            ++out.pooledCells;
            continue;
        }
        out.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++cells;
    }
    if (pooledExpected > 0) {
        out.statistic +=
            (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++cells;
    } else if (pooledObserved > 0) {
        out.failure = "samples in pooled cells whose expected count is zero";
        out.pValue = 0;
        return out;
    }
    out.degreesOfFreedom = cells - 1;
    out.pValue = out.degreesOfFreedom > 0
                     ? boost::math::gamma_q(0.5 * out.degreesOfFreedom, 0.5 * out.statistic)
                     : 1.0;
    return out;
}

double sidakAlpha(double alpha, int tests) {
    return 1.0 - std::pow(1.0 - alpha, 1.0 / tests);
}

double zThreshold(double alpha) {
    return boost::math::quantile(boost::math::normal(), 1.0 - alpha / 2.0);
}

double tThreshold(double alpha, int dof) {
    return boost::math::quantile(boost::math::students_t(dof), 1.0 - alpha / 2.0);
}

namespace {
std::string orTestName(std::string what) {
    return what.empty() ? ::testing::UnitTest::GetInstance()->current_test_info()->name() : what;
}
}  // namespace

void Chi2Family::expectFits(const Chi2Outcome& r, std::string what) const {
    what = orTestName(std::move(what));
    std::printf("[chi2] %s: %s\n", what.c_str(), r.describe().c_str());
    EXPECT_TRUE(r.passes(alpha_)) << what << ": " << r.describe() << " (alpha " << alpha_ << ")";
}

void Chi2Family::expectRejects(const Chi2Outcome& r, std::string what) const {
    what = orTestName(std::move(what));
    std::printf("[chi2, negative control] %s: %s\n", what.c_str(), r.describe().c_str());
    EXPECT_FALSE(r.passes(alpha_)) << what << ": " << r.describe() << " (alpha " << alpha_ << ")";
}

}  // namespace rr::test
