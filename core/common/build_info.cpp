#include "common/build_info.hpp"

#include <CGAL/version.h>
#include <cholmod.h>
#include <omp.h>

#include <Eigen/Core>
#include <sstream>

#include "common/thread_budget.hpp"

namespace progsim {

const char* version_string() {
  return PROGSIM_VERSION_STRING;
}

std::string build_info() {
  std::ostringstream out;
  out << "progsim " << version_string() << "\n"
      << "compiler: " << __VERSION__ << "\n"
#ifdef NDEBUG
      << "assertions: off\n"
#else
      << "assertions: on\n"
#endif
#if defined(__SANITIZE_ADDRESS__)
      << "sanitizers: address\n"
#endif
      << "openmp threads: " << omp_get_max_threads() << "\n"
      << "thread budget: " << (thread_budget_setting() == 0 ? "automatic" : "fixed") << ", now "
      << thread_budget() << "\n"
      << "eigen: " << EIGEN_WORLD_VERSION << "." << EIGEN_MAJOR_VERSION << "."
      << EIGEN_MINOR_VERSION << "\n"
      << "cholmod: " << CHOLMOD_MAIN_VERSION << "." << CHOLMOD_SUB_VERSION << "."
      << CHOLMOD_SUBSUB_VERSION << "\n"
      << "cgal: " << CGAL_VERSION_STR << "\n";
  return out.str();
}

}  // namespace progsim
