// Pearson χ² goodness-of-fit, the shared tool for every sampling routine (warps, lights,
// BSDFs): histogram the samples, integrate the claimed density over each cell, pool cells
// whose expected count is below 5, and compare the p-value with a Šidák-corrected level.
#pragma once

#include <string>
#include <vector>

namespace rr::test {

struct Chi2Outcome {
    double statistic = 0;
    int degreesOfFreedom = 0;
    double pValue = 1;
    int pooledCells = 0;  // cells merged because their expected count was small
    std::string failure;  // non-empty when a sample landed where the density is zero

    bool passes(double alpha) const { return failure.empty() && pValue >= alpha; }
    std::string describe() const;
};

// `observed` and `expected` are counts per cell; their totals should agree.
Chi2Outcome chi2GoodnessOfFit(const std::vector<double>& observed,
                              const std::vector<double>& expected, double minExpected = 5.0);

// Per-test significance so that `tests` independent tests have family-wise level `alpha`.
double sidakAlpha(double alpha, int tests);

// Two-sided z-test threshold |z| for significance `alpha`.
double zThreshold(double alpha);
// Two-sided t-test threshold |t| for significance `alpha` with `dof` degrees of freedom (a mean
// whose standard error comes from the spread of dof + 1 independent values).
double tThreshold(double alpha, int dof);

// The χ² runs of one test program, Šidák-corrected to family-wise level `familyAlpha`.
// Outcomes are printed, so the p-values of passing runs are visible in the test log.
class Chi2Family {
  public:
    explicit Chi2Family(int runs, double familyAlpha = 0.01)
        : alpha_(sidakAlpha(familyAlpha, runs)) {}
    double alpha() const { return alpha_; }
    // The samples must fit the claimed density. `what` defaults to the running test's name.
    void expectFits(const Chi2Outcome& outcome, std::string what = "") const;
    // Negative control: a deliberately wrong density must be rejected, or the test is blind.
    void expectRejects(const Chi2Outcome& outcome, std::string what = "") const;

  private:
    double alpha_;
};

}  // namespace rr::test
