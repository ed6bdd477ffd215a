// stochtex - the common subset of OSL and C++ the shader headers are written in (docs/osl.md).
//
// Each osl/stochtex_*.h compiles as OSL and as C++ (the tests compile them against the core):
// float and int only, arrays passed whole, no OSL-only syntax, and outputs through these macros,
// which a C++ includer defines first (tests/osl_shim.h: references, and plain arrays, which C++
// passes by pointer anyway).
#ifndef STOCHTEX_SUBSET_H
#define STOCHTEX_SUBSET_H

#ifndef STOCHTEX_OUT
#define STOCHTEX_OUT(type) output type
#endif
#ifndef STOCHTEX_OUT_ARRAY
#define STOCHTEX_OUT_ARRAY(type) output type
#endif

#endif
