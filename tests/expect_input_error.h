#pragma once
// Runs f and returns the InputError it throws; a test failure if it throws none.
#include <gtest/gtest.h>

#include "core/error.h"

template <class F>
inim::InputError expectInputError(F f) {
  try {
    f();
  } catch (const inim::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError thrown";
  return inim::InputError("", "", "", "");
}
