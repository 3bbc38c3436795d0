// The process-wide thread count of progsim's parallel loops (core/common/thread_budget.hpp).
#include "api_guard.hpp"
#include "common/thread_budget.hpp"

using progsim::capi::guarded;

extern "C" {

PS_API int32_t ps_set_threads(int32_t threads) {
  return guarded(nullptr, "ps_set_threads", [&] { progsim::set_thread_budget(threads); });
}

PS_API int32_t ps_get_threads(int32_t* setting, int32_t* current) {
  return guarded(nullptr, "ps_get_threads", [&] {
    if (setting) *setting = progsim::thread_budget_setting();
    if (current) *current = progsim::thread_budget();
  });
}

}  // extern "C"
