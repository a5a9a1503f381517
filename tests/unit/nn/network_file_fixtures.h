#pragma once
// Shared by the network-file tests: the check that a load is refused with an InputError that names the
// file ("net.msn", the name the tests parse under) and says what is wrong.

#include <gtest/gtest.h>

#include <string>

#include "common/errors.h"

namespace motionstyle::nn::test {

// f() must throw an InputError whose message contains `needle` and whose file is "net.msn".
template <typename F>
void expectInputError(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no InputError (expected one mentioning '" << needle << "')";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(e.file(), "net.msn");
  }
}

}  // namespace motionstyle::nn::test
