#pragma once
/// @file Expecting a progsim::Error with a given status and message.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "common/error.hpp"

namespace progsim::test_support {

/// Expects `action` to throw Error(status) whose message contains each of `parts`.
template <class Action>
void expect_error(Action&& action, Status status, std::initializer_list<std::string> parts) {
  try {
    action();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), status) << status_name(e.status()) << ": " << e.what();
    for (const std::string& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message \"" << e.what() << "\" lacks \"" << part << "\"";
    return;
  }
  ADD_FAILURE() << "no progsim::Error thrown; expected " << status_name(status);
}

}  // namespace progsim::test_support
