// Doubles of small magnitude (|v| < 2^31) to integer lanes, truncated toward zero: what
// ConvertTo gives for them, cheaply. Highway's ConvertTo to int64 is about fifteen operations on
// AVX2, which has no such conversion; DemoteTo to int32 is one (plus Highway's clamp, which
// changes no such lane), and AVX-512 has both as one instruction.
//
// Included from a kernel file after hwy/highway.h, once per target (foreach_target.h): the
// guard below is Highway's per-target toggle, not a plain include guard.
#if defined(STOCHTEX_NUMERICS_SMALL_INTEGERS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef STOCHTEX_NUMERICS_SMALL_INTEGERS_INL_H_
#undef STOCHTEX_NUMERICS_SMALL_INTEGERS_INL_H_
#else
#define STOCHTEX_NUMERICS_SMALL_INTEGERS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstdint>

HWY_BEFORE_NAMESPACE();
namespace stochtex::small_integers::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// v truncated to int32 lanes (|v| < 2^31).
template <class DD>
HWY_INLINE hn::Vec<hn::Rebind<std::int32_t, DD>> SmallToInt32(DD, hn::Vec<DD> v)
{
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
    if constexpr (hn::MaxLanes(DD()) == 8) return hn::Vec<hn::Rebind<std::int32_t, DD>>{_mm512_cvttpd_epi32(v.raw)};
#endif
    return hn::DemoteTo(hn::Rebind<std::int32_t, DD>(), v);
}

/// v truncated to int64 lanes (|v| < 2^31).
template <class DD>
HWY_INLINE hn::Vec<hn::RebindToSigned<DD>> SmallToInt64(DD dd, hn::Vec<DD> v)
{
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
    if constexpr (hn::MaxLanes(DD()) == 8) return hn::Vec<hn::RebindToSigned<DD>>{_mm512_cvttpd_epi64(v.raw)};
#endif
    return hn::PromoteTo(hn::RebindToSigned<DD>(), SmallToInt32(dd, v));
}

}  // namespace stochtex::small_integers::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // STOCHTEX_NUMERICS_SMALL_INTEGERS_INL_H_ toggle
