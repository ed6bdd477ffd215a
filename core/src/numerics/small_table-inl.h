// A short table held in vector registers and read by lane permutations, for the Highway
// kernels whose tables are a few dozen entries (a monotone cubic's knots, the tile translations
// and per-vertex lookup rows of a tiling raster's tap row): a permutation per vector and a
// blend beat a gather. The values read are the table's own, so a kernel reads the same bits as
// with a gather.
//
// Included from a kernel file after hwy/highway.h, once per target (foreach_target.h): the
// guard below is Highway's per-target toggle, not a plain include guard.
#if defined(STOCHTEX_NUMERICS_SMALL_TABLE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef STOCHTEX_NUMERICS_SMALL_TABLE_INL_H_
#undef STOCHTEX_NUMERICS_SMALL_TABLE_INL_H_
#else
#define STOCHTEX_NUMERICS_SMALL_TABLE_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>
#include <type_traits>

HWY_BEFORE_NAMESPACE();
namespace stochtex::small_table::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Lane i of the two-vector table (low, high) at index[i] (in [0, 2 · lanes); only the low
/// log2(2 · lanes) bits are read, so index − 2 · lanes · m reads the same). AVX-512 has it as
/// one instruction for the vectors the kernels use (vpermt2pd, vpermt2ps, vpermt2d; Highway 1.0
/// names no such op); elsewhere two permutations and a blend.
template <class D>
hn::Vec<D> TwoTablesLookup(D d, hn::Vec<D> low, hn::Vec<D> high, hn::Vec<hn::RebindToSigned<D>> index)
{
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
    constexpr std::size_t bytes = hn::MaxLanes(D()) * sizeof(hn::TFromD<D>);
    if constexpr (bytes == 64 && std::is_same_v<hn::TFromD<D>, double>) {
        return hn::Vec<D>{_mm512_permutex2var_pd(low.raw, index.raw, high.raw)};
    } else if constexpr (bytes == 32 && std::is_same_v<hn::TFromD<D>, float>) {
        return hn::Vec<D>{_mm256_permutex2var_ps(low.raw, index.raw, high.raw)};
    } else if constexpr (bytes == 32 && std::is_same_v<hn::TFromD<D>, std::int32_t>) {
        return hn::Vec<D>{_mm256_permutex2var_epi32(low.raw, index.raw, high.raw)};
    }
#endif
    const hn::RebindToSigned<D> di;
    const auto lanes = hn::Set(di, hn::TFromD<decltype(di)>(hn::Lanes(d)));
    const auto lane = hn::IndicesFromVec(d, hn::And(index, hn::Sub(lanes, hn::Set(di, 1))));
    const auto in_high = hn::RebindMask(d, hn::Eq(hn::And(index, lanes), lanes));
    return hn::IfThenElse(in_high, hn::TableLookupLanes(high, lane), hn::TableLookupLanes(low, lane));
}

/// Vectors 0 … n − 1 of `values`: count entries, the rest zero; the first `readable` ≥ count
/// entries may be read as whole vectors (a caller's padding: their values are never looked up).
template <class D>
void LoadTable(D d, const hn::TFromD<D>* values, std::size_t count, std::size_t readable, hn::Vec<D>* vectors, std::size_t n)
{
    const std::size_t lanes = hn::Lanes(d);
    for (std::size_t v = 0; v < n; ++v) {
        if ((v + 1) * lanes <= readable) {
            vectors[v] = hn::LoadU(d, values + v * lanes);
        } else if (v * lanes < count) {
            hn::TFromD<D> chunk[hn::MaxLanes(D())] = {};
            for (std::size_t k = 0; k < lanes && v * lanes + k < count; ++k) chunk[k] = values[v * lanes + k];
            vectors[v] = hn::LoadU(d, chunk);
        } else {
            vectors[v] = hn::Zero(d);
        }
    }
}

/// Where each lane's entry lies in a table of `Vectors` vectors of D's lanes: its lane in a
/// vector and, for each vector v ≥ 1, whether the entry is in v or past it. It depends on the
/// index alone, so reads of several tables at the same entries (a monotone cubic's six knot
/// arrays) locate once and pay only their permutations and blends.
template <class D, std::size_t Vectors>
struct SmallTableIndex {
    static_assert(Vectors >= 1 && Vectors <= 4, "a SmallTable holds 1 to 4 vectors");
    using Index = hn::Vec<hn::RebindToSigned<D>>;
    Index index;
    decltype(hn::IndicesFromVec(D(), Index())) lane;
    hn::Mask<D> past[Vectors > 1 ? Vectors - 1 : 1];  // past[v − 1]: index ≥ v · lanes

    SmallTableIndex(D d, Index entry) : index(entry), lane(hn::IndicesFromVec(d, hn::And(entry, LaneMask(d))))
    {
        const hn::RebindToSigned<D> di;
        using TI = hn::TFromD<decltype(di)>;
        for (std::size_t v = 1; v < Vectors; ++v)
            past[v - 1] = hn::RebindMask(d, hn::Gt(entry, hn::Set(di, TI(TI(v) * TI(hn::Lanes(d)) - 1))));
    }

private:
    static Index LaneMask(D d)
    {
        using TI = hn::TFromD<hn::RebindToSigned<D>>;
        return hn::Set(hn::RebindToSigned<D>(), TI(TI(hn::Lanes(d)) - 1));
    }
};

/// A table of up to 4 vectors of D's lanes; operator() reads entry index[i] into lane i
/// (indices in [0, count): the caller's). Where the target has a two-table permutation
/// (AVX-512) it reads a pair of vectors at a time; elsewhere a permutation per vector and a
/// blend for each vector after the first.
template <class D>
class SmallTable {
public:
    using T = hn::TFromD<D>;
    static constexpr std::size_t max_vectors = 4;
    /// `readable` as LoadTable's.
    SmallTable(D d, const T* values, std::size_t count, std::size_t readable = 0)
        : vectors_((count + hn::Lanes(d) - 1) / hn::Lanes(d))
    {
        LoadTable(d, values, count, readable, table_, max_vectors);
    }
    static bool fits(D d, std::size_t count) { return count <= max_vectors * hn::Lanes(d); }
    /// The vectors holding the table's entries (the rest are zero: a read with a larger
    /// SmallTableIndex gives the same values).
    std::size_t vectors() const { return vectors_; }
    hn::Vec<D> operator()(D d, hn::Vec<hn::RebindToSigned<D>> index) const
    {
        switch (vectors_) {
            case 1: return (*this)(d, SmallTableIndex<D, 1>(d, index));
            case 2: return (*this)(d, SmallTableIndex<D, 2>(d, index));
            case 3: return (*this)(d, SmallTableIndex<D, 3>(d, index));
            default: return (*this)(d, SmallTableIndex<D, 4>(d, index));
        }
    }
    template <std::size_t Vectors>
    hn::Vec<D> operator()(D d, const SmallTableIndex<D, Vectors>& at) const
    {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
        auto value = TwoTablesLookup(d, table_[0], table_[1], at.index);
        if constexpr (Vectors > 2) value = hn::IfThenElse(at.past[1], TwoTablesLookup(d, table_[2], table_[3], at.index), value);
        return value;
#else
        (void)d;
        auto value = hn::TableLookupLanes(table_[0], at.lane);
        for (std::size_t v = 1; v < Vectors; ++v) value = hn::IfThenElse(at.past[v - 1], hn::TableLookupLanes(table_[v], at.lane), value);
        return value;
#endif
    }

private:
    std::size_t vectors_;
    hn::Vec<D> table_[max_vectors];
};

/// A table of up to 2 vectors, read by one two-table permutation (TwoTablesLookup): no count
/// to test per read.
template <class D>
class PairTable {
public:
    using T = hn::TFromD<D>;
    PairTable(D d, const T* values, std::size_t count, std::size_t readable = 0) { LoadTable(d, values, count, readable, table_, 2); }
    static bool fits(D d, std::size_t count) { return count <= 2 * hn::Lanes(d); }
    hn::Vec<D> operator()(D d, hn::Vec<hn::RebindToSigned<D>> index) const { return TwoTablesLookup(d, table_[0], table_[1], index); }

private:
    hn::Vec<D> table_[2];
};

}  // namespace stochtex::small_table::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // STOCHTEX_NUMERICS_SMALL_TABLE_INL_H_ toggle
