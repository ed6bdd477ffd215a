// stochtex - the common subset of OSL and C++ the shader headers are written in (docs/osl.md),
// and the row order of the host's texture() lookups, which every data lookup goes through.
//
// Each osl/stochtex_*.h compiles as OSL and as C++ (the tests compile them against the core):
// float and int only, arrays passed whole, no OSL-only syntax, and outputs through these macros,
// which a C++ includer defines first (tests/osl_shim.h: references, and plain arrays, which C++
// passes by pointer anyway; and its texture(), declared before this file).
#ifndef STOCHTEX_SUBSET_H
#define STOCHTEX_SUBSET_H

#ifndef STOCHTEX_OUT
#define STOCHTEX_OUT(type) output type
#endif
#ifndef STOCHTEX_OUT_ARRAY
#define STOCHTEX_OUT_ARRAY(type) output type
#endif

// Rows. OIIO's texture() (testshade, Cycles 4.5) reads t = 0 at an image's top row; Cycles 5.2
// serves a texture() of a constant file name through its own image manager, whose rows run
// bottom-up, so there every closest-texel lookup would read the row mirrored in t. Rather than
// name hosts, the shader asks the host: `stex osl` writes beside the data images a probe,
// stochtex_rows.exr (8 x 8 texels, the top 4 rows 0, the bottom 4 rows 1), and the shader reads
// one texel of its top half once per shading point. A missing probe reads 0: top-down.
int stochtex_rows_bottom_up(string probe)
{
    float top = texture(probe, 0.5, 0.25, "interp", "closest", "width", 0.0);
    return top > 0.5 ? 1 : 0;
}

// The t at which the host returns the texel a data image holds at t (a texel centre maps to a
// texel centre; where rows run top-down, t itself, so renders there are unchanged bit for bit).
float stochtex_row_t(float t, int rows_bottom_up)
{
    return rows_bottom_up ? 1.0 - t : t;
}

#endif
