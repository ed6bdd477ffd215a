// stochtex — errors.
// The core reports every problem with bad input (a file, a field, an option) by throwing
// stochtex::Error whose message names the thing and the problem, e.g.
//   "t.stex: parameters.band_weights[1]: expected an array of numbers, got a string".
// Front-ends catch it once: the CLI prints it and exits non-zero, the OIIO plugin turns it into
// errorfmt(). Nothing in the core prints or exits.
#pragma once

#include <stdexcept>
#include <string>

namespace stochtex {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace stochtex
