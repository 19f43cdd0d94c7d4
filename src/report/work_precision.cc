// Scaffold: replaced by the work-precision report in progress.
#include "report/work_precision.h"

#include <stdexcept>

namespace rockbench::report {

std::filesystem::path WriteSweepReport(const std::filesystem::path& sweep_dir,
                                       const std::filesystem::path&) {
  throw std::runtime_error(sweep_dir.string() + ": sweep reports are not built yet");
}

}  // namespace rockbench::report
