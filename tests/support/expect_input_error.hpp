#pragma once
// For the I/O tests: a whole-input failure must be an InputError whose message is one line
// naming what is wrong (file name, line number, field path ...).
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "bezinv/io.hpp"

namespace bezinv::test_support {

// Runs `read`, expects InputError, and checks that the message is one line containing every fragment.
template <class Read>
void expect_input_error(Read read, std::initializer_list<std::string> fragments) {
  try {
    read();
    ADD_FAILURE() << "no InputError; expected one mentioning " << *fragments.begin();
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    for (const std::string& fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << message;
  }
}

}  // namespace bezinv::test_support
