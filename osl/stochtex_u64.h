// stochtex - 64-bit unsigned integer arithmetic for OSL shaders (docs/osl.md).
//
// The core draws its random numbers with 64-bit SplitMix64 mixing (numerics/random.h, the gabor
// impulses, the tiling offsets). OSL has only 32-bit signed ints, whose overflow C++ leaves
// undefined, so a 64-bit value is held here as four 16-bit limbs (int a[4], a[0] the least
// significant), and every intermediate stays in [0, 2^31): products are of a 16-bit limb by an
// 8-bit half limb. The results are the core's bits exactly, in OSL and in C++ alike
// (tests/osl_gabor_test.cpp and osl_tiling_test.cpp compare them with the core's draws).
//
// Written in the common subset of OSL and C++ (see stochtex_wavelet.h): outputs through
// STOCHTEX_OUT / STOCHTEX_OUT_ARRAY, and every function may be called with its output aliasing
// an input (results go through a local first).
#ifndef STOCHTEX_U64_H
#define STOCHTEX_U64_H

#include "stochtex_subset.h"

// Integer min and max: older OSL releases have them for float only.
int stochtex_min_int(int a, int b)
{
    return a < b ? a : b;
}

int stochtex_max_int(int a, int b)
{
    return a > b ? a : b;
}

void stochtex_u64_set(int l0, int l1, int l2, int l3, STOCHTEX_OUT_ARRAY(int) r[4])
{
    r[0] = l0;
    r[1] = l1;
    r[2] = l2;
    r[3] = l3;
}

void stochtex_u64_copy(int a[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    for (int k = 0; k < 4; ++k)
        r[k] = a[k];
}

// The two's-complement bits of a signed 32-bit int widened to 64 bits (C++'s uint64_t(int64_t(i))).
void stochtex_u64_from_int(int i, STOCHTEX_OUT_ARRAY(int) r[4])
{
    if (i >= 0) {
        stochtex_u64_set(i % 65536, i / 65536, 0, 0, r);
    } else {
        int m = -(i + 1);  // ~i, non-negative for every i (no overflow at the most negative int)
        stochtex_u64_set(65535 - m % 65536, 65535 - m / 65536, 65535, 65535, r);
    }
}

void stochtex_u64_add(int a[4], int b[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    int t[4];
    int carry = 0;
    for (int k = 0; k < 4; ++k) {
        int s = a[k] + b[k] + carry;
        t[k] = s & 65535;
        carry = s >> 16;
    }
    stochtex_u64_copy(t, r);
}

void stochtex_u64_xor(int a[4], int b[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    for (int k = 0; k < 4; ++k)
        r[k] = a[k] ^ b[k];
}

// a * b modulo 2^64.
void stochtex_u64_mul(int a[4], int b[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    int column[5] = { 0, 0, 0, 0, 0 };
    for (int k = 0; k < 4; ++k) {
        for (int i = 0; i <= k; ++i) {
            int low = a[i] * (b[k - i] & 255);  // < 2^24
            int high = a[i] * (b[k - i] >> 8);  // < 2^24, weight 2^8
            column[k] += (low & 65535) + ((high & 255) << 8);
            column[k + 1] += (low >> 16) + (high >> 8);
        }
    }
    int t[4];
    int carry = 0;
    for (int k = 0; k < 4; ++k) {
        int s = column[k] + carry;
        t[k] = s & 65535;
        carry = s >> 16;
    }
    stochtex_u64_copy(t, r);
}

// a >> n, 0 <= n < 64.
void stochtex_u64_shift_right(int a[4], int n, STOCHTEX_OUT_ARRAY(int) r[4])
{
    int q = n / 16, s = n % 16;
    int t[4];
    for (int k = 0; k < 4; ++k) {
        int shifted = 0;
        if (k + q < 4)
            shifted = a[k + q] >> s;
        if (k + q + 1 < 4)
            shifted = shifted | ((a[k + q + 1] & ((1 << s) - 1)) << (16 - s));
        t[k] = shifted;
    }
    stochtex_u64_copy(t, r);
}

// a ^ (a >> n), 0 < n < 64: SplitMix64's xorshift step.
void stochtex_u64_xorshift(int a[4], int n, STOCHTEX_OUT_ARRAY(int) r[4])
{
    int shifted[4];
    stochtex_u64_shift_right(a, n, shifted);
    stochtex_u64_xor(a, shifted, r);
}

// (a >> shift) & (2^count - 1), count <= 24: as an int, exactly convertible to float.
int stochtex_u64_bits(int a[4], int shift, int count)
{
    int result = 0, got = 0, position = shift;
    while (got < count && position < 64) {
        int limb = position / 16, offset = position % 16;
        int take = stochtex_min_int(16 - offset, count - got);
        result += ((a[limb] >> offset) & ((1 << take) - 1)) << got;
        got += take;
        position += take;
    }
    return result;
}

// a < b as unsigned 64-bit integers: 1 or 0 (decided by the most significant differing limb;
// no return inside the loop, which OSL compilers of every age accept).
int stochtex_u64_less(int a[4], int b[4])
{
    int less = 0, decided = 0;
    for (int k = 3; k >= 0; --k) {
        if (decided == 0 && a[k] != b[k]) {
            less = a[k] < b[k] ? 1 : 0;
            decided = 1;
        }
    }
    return less;
}

// SplitMix64's output function (Steele et al. 2014), the core's mix64.
void stochtex_mix64(int a[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    int m1[4] = { 58809, 7396, 18285, 48984 };  // 0xbf58476d1ce4e5b9
    int m2[4] = { 4587, 4913, 18875, 38096 };   // 0x94d049bb133111eb
    int t[4];
    stochtex_u64_xorshift(a, 30, t);
    stochtex_u64_mul(t, m1, t);
    stochtex_u64_xorshift(t, 27, t);
    stochtex_u64_mul(t, m2, t);
    stochtex_u64_xorshift(t, 31, r);
}

// SplitMix64::next(): state += the golden gamma, returns the mix of the new state.
void stochtex_splitmix_next(STOCHTEX_OUT_ARRAY(int) state[4], STOCHTEX_OUT_ARRAY(int) r[4])
{
    int golden[4] = { 31765, 32586, 31161, 40503 };  // 0x9e3779b97f4a7c15
    stochtex_u64_add(state, golden, state);
    stochtex_mix64(state, r);
}

#endif
