// A short table of doubles held in vector registers and read by lane permutations, for the
// Highway kernels whose tables are a few dozen entries (a monotone cubic's knots, the tile
// translations of a tiling raster's tap row): a permutation per vector and a blend beat a gather.
// The values read are the table's own, so a kernel reads the same bits as with a gather.
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

HWY_BEFORE_NAMESPACE();
namespace stochtex::small_table::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// A table of up to 4 vectors of doubles; operator() reads entry index[i] into lane i (indices
/// in [0, count): the caller's).
template <class D>
class SmallTable {
public:
    static constexpr std::size_t max_vectors = 4;
    SmallTable(D d, const double* values, std::size_t count) : vectors_((count + hn::Lanes(d) - 1) / hn::Lanes(d))
    {
        const std::size_t lanes = hn::Lanes(d);
        for (std::size_t v = 0; v < vectors_; ++v) {
            double chunk[hn::MaxLanes(D())] = {};
            for (std::size_t k = 0; k < lanes && v * lanes + k < count; ++k) chunk[k] = values[v * lanes + k];
            table_[v] = hn::LoadU(d, chunk);
        }
    }
    static bool fits(D d, std::size_t count) { return count <= max_vectors * hn::Lanes(d); }
    hn::Vec<D> operator()(D d, hn::Vec<hn::RebindToSigned<D>> index) const
    {
        const hn::RebindToSigned<D> di;
        const std::int64_t lanes = std::int64_t(hn::Lanes(d));
        const auto lane = hn::IndicesFromVec(d, hn::And(index, hn::Set(di, lanes - 1)));
        auto value = hn::TableLookupLanes(table_[0], lane);
        for (std::size_t v = 1; v < vectors_; ++v) {
            const auto in_vector = hn::RebindMask(d, hn::Gt(index, hn::Set(di, std::int64_t(v) * lanes - 1)));
            value = hn::IfThenElse(in_vector, hn::TableLookupLanes(table_[v], lane), value);
        }
        return value;
    }

private:
    std::size_t vectors_;
    hn::Vec<D> table_[max_vectors];
};

}  // namespace stochtex::small_table::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // STOCHTEX_NUMERICS_SMALL_TABLE_INL_H_ toggle
