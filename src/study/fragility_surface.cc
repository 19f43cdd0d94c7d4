#include "study/fragility_surface.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_sf_erf.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "statistics/statistics.h"

namespace rockbench::stats {
namespace {

double LogPhi(double z) {
  return gsl_sf_log_erfc(-z / std::sqrt(2.0)) - std::log(2.0);
}

struct Data {
  std::vector<double> x1, x2;  // ln PGA, ln(r / r_ref)
  std::vector<char> failed;
};

// -log-likelihood at p = (m0, m1, ln beta) and its gradient (g may be null).
double NegLogLikelihood(const Data& d, const gsl_vector* p, gsl_vector* g) {
  const double m0 = gsl_vector_get(p, 0), m1 = gsl_vector_get(p, 1);
  const double beta = std::exp(gsl_vector_get(p, 2));
  double nll = 0.0, g0 = 0.0, g1 = 0.0, g2 = 0.0;
  for (size_t i = 0; i < d.x1.size(); ++i) {
    const double z = (d.x1[i] - m0 - m1 * d.x2[i]) / beta;
    // d(-ln P)/dz: -phi/Phi for a failure, +phi/Q for a survival (GSL's hazard is phi/Q).
    double dz = 0.0;
    if (d.failed[i]) {
      nll -= LogPhi(z);
      dz = -gsl_sf_hazard(-z);
    } else {
      nll -= LogPhi(-z);
      dz = gsl_sf_hazard(z);
    }
    // dz/dm0 = -1/beta, dz/dm1 = -x2/beta, dz/d(ln beta) = -z.
    g0 -= dz / beta;
    g1 -= dz * d.x2[i] / beta;
    g2 -= dz * z;
  }
  if (g != nullptr) {
    gsl_vector_set(g, 0, g0);
    gsl_vector_set(g, 1, g1);
    gsl_vector_set(g, 2, g2);
  }
  return nll;
}

double F(const gsl_vector* x, void* p) {
  return NegLogLikelihood(*static_cast<const Data*>(p), x, nullptr);
}
void Df(const gsl_vector* x, void* p, gsl_vector* g) {
  NegLogLikelihood(*static_cast<const Data*>(p), x, g);
}
void Fdf(const gsl_vector* x, void* p, double* f, gsl_vector* g) {
  *f = NegLogLikelihood(*static_cast<const Data*>(p), x, g);
}

}  // namespace

double FragilitySurface::PgaAt(double p, double ratio_s) const {
  return std::exp(m0 + beta * gsl_cdf_ugaussian_Pinv(p) + m1 * std::log(ratio_s / ratio_ref_s));
}

FragilitySurface FitFragilitySurface(std::span<const SurfacePoint> points, double ratio_ref_s) {
  FragilitySurface fit;
  fit.ratio_ref_s = ratio_ref_s;
  Data d;
  for (const SurfacePoint& q : points) {
    if (!(q.pga > 0.0) || !std::isfinite(q.pga) || !(q.ratio_s > 0.0) ||
        !std::isfinite(q.ratio_s)) {
      throw std::invalid_argument("fragility surface: PGA and PGV/PGA must be positive and finite");
    }
    d.x1.push_back(std::log(q.pga));
    d.x2.push_back(std::log(q.ratio_s / ratio_ref_s));
    d.failed.push_back(q.failed);
    fit.failures += q.failed;
  }
  fit.n = static_cast<int>(d.x1.size());
  if (fit.failures == 0 || fit.failures == fit.n) {
    fit.reason = fit.failures == 0 ? "no member failed" : "every member failed";
    return fit;
  }
  double mean = 0.0, var = 0.0;
  for (double x : d.x1) mean += x / fit.n;
  for (double x : d.x1) var += (x - mean) * (x - mean) / fit.n;
  gsl_multimin_function_fdf fn{&F, &Df, &Fdf, 3, &d};
  gsl_vector* x = gsl_vector_alloc(3);
  gsl_vector_set(x, 0, mean);
  gsl_vector_set(x, 1, 0.0);
  gsl_vector_set(x, 2, std::log(std::max(std::sqrt(var), 1e-3)));
  gsl_multimin_fdfminimizer* s =
      gsl_multimin_fdfminimizer_alloc(gsl_multimin_fdfminimizer_vector_bfgs2, 3);
  gsl_multimin_fdfminimizer_set(s, &fn, x, 0.01, 0.1);
  int status = GSL_CONTINUE;
  for (int iter = 0; iter < 2000 && status == GSL_CONTINUE; ++iter) {
    if (gsl_multimin_fdfminimizer_iterate(s) != GSL_SUCCESS) break;
    status = gsl_multimin_test_gradient(s->gradient, 1e-9 * fit.n);
  }
  fit.m0 = gsl_vector_get(s->x, 0);
  fit.m1 = gsl_vector_get(s->x, 1);
  fit.beta = std::exp(gsl_vector_get(s->x, 2));
  fit.log_likelihood = -s->f;
  const double grad = gsl_blas_dnrm2(s->gradient);
  gsl_multimin_fdfminimizer_free(s);
  gsl_vector_free(x);
  // Failures and survivals that a line in the plane separates have no maximum: the likelihood
  // tends to 1 as beta -> 0, and the optimiser stops where it is flat, at a log-likelihood
  // within its gradient tolerance of 0; overlapping classes leave members with fitted
  // probabilities away from 0 and 1, each costing far more than 1e-3.
  if (!(grad <= 1e-6 * fit.n) || !std::isfinite(fit.m0) || !std::isfinite(fit.m1) ||
      !(fit.beta > 1e-6) || fit.log_likelihood > -1e-3) {
    fit.reason =
        "the likelihood has no finite maximum (failures and survivals separated by a "
        "line, or the optimiser stopped)";
    return fit;
  }
  fit.available = true;
  return fit;
}

SurfaceMedianRatio PairedSurfaceRatio(std::span<const SurfacePoint> reference,
                                      std::span<const SurfacePoint> engine,
                                      std::span<const double> at_ratio_s, int bootstrap,
                                      std::uint64_t seed, double level, double ratio_ref_s) {
  if (reference.size() != engine.size()) {
    throw std::invalid_argument("PairedSurfaceRatio: the two runs must have the same members");
  }
  if (!(level > 0.0 && level < 1.0)) {
    throw std::invalid_argument("PairedSurfaceRatio: level must be in (0, 1)");
  }
  for (const double r : at_ratio_s) {
    if (!(r > 0.0) || !std::isfinite(r)) {
      throw std::invalid_argument("PairedSurfaceRatio: ratios must be positive and finite");
    }
  }
  SurfaceMedianRatio out;
  out.ratio_s.assign(at_ratio_s.begin(), at_ratio_s.end());
  const FragilitySurface a = FitFragilitySurface(reference, ratio_ref_s);
  const FragilitySurface b = FitFragilitySurface(engine, ratio_ref_s);
  if (!a.available || !b.available) {
    out.reason = "no fit: " + (a.available ? b.reason : a.reason);
    return out;
  }
  for (const double r : at_ratio_s) out.estimate.push_back(b.PgaAt(0.5, r) / a.PgaAt(0.5, r));
  // The same members drawn for both runs, both surfaces refitted.
  const size_t n = reference.size();
  std::vector<SurfacePoint> ra(n), rb(n);
  const BootstrapDraws draws =
      Bootstrap(n, bootstrap, seed, at_ratio_s.size(),
                [&](std::span<const size_t> members, std::vector<double>& ratios) {
                  for (size_t i = 0; i < n; ++i) {
                    ra[i] = reference[members[i]];
                    rb[i] = engine[members[i]];
                  }
                  const FragilitySurface fa = FitFragilitySurface(ra, ratio_ref_s);
                  const FragilitySurface fb = FitFragilitySurface(rb, ratio_ref_s);
                  if (!fa.available || !fb.available) return false;
                  for (size_t q = 0; q < at_ratio_s.size(); ++q) {
                    ratios[q] = fb.PgaAt(0.5, at_ratio_s[q]) / fa.PgaAt(0.5, at_ratio_s[q]);
                  }
                  return true;
                });
  out.resamples = draws.resamples;
  out.degenerate = draws.degenerate;
  // Fewer than 20 usable resamples give no interval worth the name.
  if (bootstrap - out.degenerate < 20) {
    out.reason = "too few resamples with a fit on both sides (" +
                 std::to_string(bootstrap - out.degenerate) + " of " + std::to_string(bootstrap) +
                 ")";
    return out;
  }
  const double tail = 0.5 * (1.0 - level);
  for (const std::vector<double>& v : draws.values) {
    out.lo.push_back(LowerOrderPercentile(v, tail));
    out.hi.push_back(LowerOrderPercentile(v, 1.0 - tail));
  }
  out.available = true;
  return out;
}

}  // namespace rockbench::stats
