// Typed errors of the pinmask libraries. Libraries throw; only cli/ maps them to exit codes:
// InvalidInput -> 2 (usage or bad input), everything else -> 1 (runtime failure).
#pragma once

#include <stdexcept>
#include <string>

namespace pinmask {

// Base of every error the libraries throw on purpose.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The caller's input is wrong: a field, a value and the rule it breaks. Exit code 2.
class InvalidInput : public Error {
  public:
    using Error::Error;
};

// A request that would exceed a resource bound (memory, size); refused before allocating.
// Counts as invalid input (exit 2): the request, not the machine, is at fault.
class ResourceLimit : public InvalidInput {
  public:
    using InvalidInput::InvalidInput;
};

// Something failed while doing valid work (I/O error, solver breakdown). Exit code 1.
class RuntimeFailure : public Error {
  public:
    using Error::Error;
};

// Builds "field = value: rule" messages uniformly. A settings field is named as a reference
// that each face spells its own way (core/errors/field_names.hpp):
//   invalid_field(field_ref("iterations"), "0", "must be >= 1")
// prints "iters = 0: ..." from Python, and the command line prints its flag for `iterations`
// (cli/options/flag_names) in the same place.
InvalidInput invalid_field(const std::string& field, const std::string& value,
                           const std::string& rule);

}  // namespace pinmask
