// The parameters of the test suite's model that declares every capability
// (test_everything_model.cpp), shared with its front-end forms beside it.
#pragma once

namespace stochtex::test {

struct TestEverythingParameters {
    double frequency = 4;  ///< lattice cells per texture unit
    double amplitude = 0.1;
};

}  // namespace stochtex::test
