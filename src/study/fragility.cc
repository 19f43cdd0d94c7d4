#include "study/fragility.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_sf_erf.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <random>
#include <stdexcept>
#include <vector>

#include "statistics/statistics.h"
#include "util/format.h"

namespace rockbench::stats {
namespace {

// ln Phi(z), stable in both tails.
double LogPhi(double z) {
  return gsl_sf_log_erfc(-z / std::sqrt(2.0)) - std::log(2.0);
}

struct Data {
  std::vector<double> log_im;
  std::vector<char> failed;
};

// -log-likelihood at (u, v) = (ln median, ln beta), and its gradient.
double NegLogLikelihood(const Data& d, double u, double v, double* du, double* dv) {
  const double beta = std::exp(v);
  double nll = 0.0, gu = 0.0, gv = 0.0;
  for (size_t i = 0; i < d.log_im.size(); ++i) {
    const double z = (d.log_im[i] - u) / beta;
    // d ln P / dz: phi/Phi for a failure, -phi/Q for a survival (GSL's hazard: phi/Q).
    double dz = 0.0;
    if (d.failed[i]) {
      nll -= LogPhi(z);
      dz = gsl_sf_hazard(-z);
    } else {
      nll -= LogPhi(-z);
      dz = -gsl_sf_hazard(z);
    }
    // dz/du = -1/beta, dz/dv = -z.
    gu += dz / beta;
    gv += dz * z;
  }
  if (du) *du = gu;
  if (dv) *dv = gv;
  return nll;
}

double F(const gsl_vector* x, void* p) {
  return NegLogLikelihood(*static_cast<const Data*>(p), gsl_vector_get(x, 0), gsl_vector_get(x, 1),
                          nullptr, nullptr);
}
void Df(const gsl_vector* x, void* p, gsl_vector* g) {
  double du = 0, dv = 0;
  NegLogLikelihood(*static_cast<const Data*>(p), gsl_vector_get(x, 0), gsl_vector_get(x, 1), &du,
                   &dv);
  gsl_vector_set(g, 0, du);
  gsl_vector_set(g, 1, dv);
}
void Fdf(const gsl_vector* x, void* p, double* f, gsl_vector* g) {
  double du = 0, dv = 0;
  *f = NegLogLikelihood(*static_cast<const Data*>(p), gsl_vector_get(x, 0), gsl_vector_get(x, 1),
                        &du, &dv);
  gsl_vector_set(g, 0, du);
  gsl_vector_set(g, 1, dv);
}

// The fit without bootstrap.
LognormalFragility FitOnce(const Data& d) {
  LognormalFragility fit;
  fit.n = static_cast<int>(d.log_im.size());
  double max_survived = -INFINITY, min_failed = INFINITY;
  for (size_t i = 0; i < d.log_im.size(); ++i) {
    if (d.failed[i]) {
      ++fit.failures;
      min_failed = std::min(min_failed, d.log_im[i]);
    } else {
      max_survived = std::max(max_survived, d.log_im[i]);
    }
  }
  if (fit.failures == 0) {
    fit.reason = "no member failed";
    return fit;
  }
  if (fit.failures == fit.n) {
    fit.reason = "every member failed";
    return fit;
  }
  if (max_survived < min_failed) {
    fit.reason = "failures and survivals are separated by the IM (every survival below " +
                 Format("%.4g", std::exp(min_failed)) +
                 ", every failure at or above it): the "
                 "median lies between " +
                 Format("%.4g", std::exp(max_survived)) + " and " +
                 Format("%.4g", std::exp(min_failed)) + " and beta -> 0";
    return fit;
  }
  // Start: the mean and standard deviation of ln IM over the members.
  double mean = 0.0, var = 0.0;
  for (double x : d.log_im) mean += x / fit.n;
  for (double x : d.log_im) var += (x - mean) * (x - mean) / fit.n;
  gsl_multimin_function_fdf fn;
  fn.n = 2;
  fn.f = &F;
  fn.df = &Df;
  fn.fdf = &Fdf;
  fn.params = const_cast<Data*>(&d);
  gsl_vector* x = gsl_vector_alloc(2);
  gsl_vector_set(x, 0, mean);
  gsl_vector_set(x, 1, std::log(std::max(std::sqrt(var), 1e-3)));
  gsl_multimin_fdfminimizer* s =
      gsl_multimin_fdfminimizer_alloc(gsl_multimin_fdfminimizer_vector_bfgs2, 2);
  gsl_multimin_fdfminimizer_set(s, &fn, x, 0.01, 0.1);
  int status = GSL_CONTINUE;
  for (int iter = 0; iter < 1000 && status == GSL_CONTINUE; ++iter) {
    if (gsl_multimin_fdfminimizer_iterate(s) != GSL_SUCCESS) break;
    status = gsl_multimin_test_gradient(s->gradient, 1e-9 * fit.n);
  }
  fit.median = std::exp(gsl_vector_get(s->x, 0));
  fit.beta = std::exp(gsl_vector_get(s->x, 1));
  fit.log_likelihood = -s->f;
  const double grad = gsl_blas_dnrm2(s->gradient);
  gsl_multimin_fdfminimizer_free(s);
  gsl_vector_free(x);
  if (!(grad <= 1e-6 * fit.n) || !std::isfinite(fit.median) || !std::isfinite(fit.beta)) {
    fit.reason = "the likelihood's maximum was not reached (gradient " + Format("%.3g", grad) + ")";
    return fit;
  }
  fit.available = true;
  return fit;
}

}  // namespace

double FragilityAt(const LognormalFragility& fit, double im) {
  if (!fit.available) return NAN;
  return gsl_cdf_ugaussian_P(std::log(im / fit.median) / fit.beta);
}

LognormalFragility FitLognormalFragility(std::span<const FragilityPoint> points, int bootstrap,
                                         std::uint64_t seed, double level) {
  if (!(level > 0.0 && level < 1.0)) {
    throw std::invalid_argument("fragility: the bootstrap level must be in (0, 1)");
  }
  Data d;
  for (const FragilityPoint& p : points) {
    if (!(p.im > 0.0) || !std::isfinite(p.im)) {
      throw std::invalid_argument(
          "fragility: an intensity measure must be positive and finite, got " +
          Format("%.6g", p.im));
    }
    d.log_im.push_back(std::log(p.im));
    d.failed.push_back(p.failed ? 1 : 0);
  }
  // GSL's default handler aborts; here an error is a result (a fit not available). Turned off
  // once for the process: the handler is global, and fits may run on several threads.
  static std::once_flag handler_off;
  std::call_once(handler_off, [] { gsl_set_error_handler_off(); });
  LognormalFragility fit = FitOnce(d);
  fit.level = level;
  if (fit.available && bootstrap > 0) {
    std::mt19937_64 rng(seed);
    std::vector<double> medians, betas;
    Data r;
    r.log_im.resize(d.log_im.size());
    r.failed.resize(d.failed.size());
    for (int b = 0; b < bootstrap; ++b) {
      for (size_t i = 0; i < d.log_im.size(); ++i) {
        const size_t k = UniformBelow(rng, d.log_im.size());
        r.log_im[i] = d.log_im[k];
        r.failed[i] = d.failed[k];
      }
      const LognormalFragility rf = FitOnce(r);
      if (!rf.available) {
        ++fit.bootstrap_degenerate;
        continue;
      }
      medians.push_back(rf.median);
      betas.push_back(rf.beta);
    }
    fit.bootstrap = bootstrap;
    if (!medians.empty()) {
      const double lo = 0.5 * (1.0 - level), hi = 1.0 - lo;
      fit.median_lo = Quantile(medians, lo);
      fit.median_hi = Quantile(medians, hi);
      fit.beta_lo = Quantile(betas, lo);
      fit.beta_hi = Quantile(betas, hi);
    }
  }
  return fit;
}

}  // namespace rockbench::stats
