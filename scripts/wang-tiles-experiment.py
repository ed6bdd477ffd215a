#!/usr/bin/env python3
"""Prototype of a quilted Wang tile set (issue 33): its synthesis, to be scored by `stex compare`.

Cohen, Shade, Hiller, Deussen, "Wang Tiles for Image and Texture Generation" (SIGGRAPH 2003),
with the seams of Efros & Freeman, "Image Quilting" (SIGGRAPH 2001); random access by hashing
the lattice's edges (no scan-order tiling).

    scripts/wang-tiles-experiment.py PHOTO.png OUT.png [-T 256] [-C 2] [-k 1] [--seed 1]
        [--band 0.25] [--separation 0] [--control] [--size WxH] [--side-by-side SBS.png] [--atlas TILES.png]

1. Samples: C colours for horizontal edges, C for vertical edges; one T x T crop of the photo per
   colour (seeded random positions; with -k K, the best of K random sets of 2C positions: the
   one whose 4 C^2 minimum-error cuts have the least total squared error; --separation S keeps
   the sample centres S*T apart in L1 so the set cannot collapse onto one patch).
2. Tiles (C^4): tile (N, E, S, W) takes, in each triangle cut by the diagonals, its edge's
   sample placed with the sample's centre line on that edge: N triangle pixel (x, y) from
   sample_N(x, y + T/2), S from sample_S(x, y - T/2), W from sample_W(x + T/2, y),
   E from sample_E(x - T/2, y). Two tiles sharing an edge colour are continuous across it.
   Each half-diagonal (centre to corner) is replaced by a minimum-error cut: dynamic
   programming over the squared sRGB difference of its two samples, on a 4-connected path
   from the corner to the centre, within a band of half-width band*T (in anti-diagonal steps)
   that narrows to zero at the corner and at the centre, so the tile's edge pixels stay the
   edge samples' (the corner pixel is the N or S sample's). No blending. A cut depends only
   on its two edges' colours: 4 C^2 cuts serve all C^4 tiles.
3. Synthesis: lattice cell (i, j) = pixels [iT, iT+T) x [jT, jT+T); horizontal edge (i, j)
   (top of cell (i, j)) has colour hash(i, j, 0, seed) mod C, vertical edge (i, j) (left of
   cell (i, j)) hash(i, j, 1, seed) mod C; the cell shows the tile (N, E, S, W) =
   (h(i,j), v(i+1,j), h(i,j+1), v(i,j)). Any pixel is computable alone: deterministic,
   random access.
4. Writes OUT.png (8-bit, the photo's sRGB values copied: same encoding) and prints the tile
   set's raw size (C^4 T^2 x 3 bytes), the samples' (2C T^2 x 3 bytes: the tiles rebuilt from
   them at load), and how much of the synthesis is distinct content.

Needs numpy. Reads PNG with PIL if present, else through `oiiotool` (PPM); writes PNG itself.
"""
import argparse
import os
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np


# ---------------------------------------------------------------- image I/O

def read_png(path):
    """8-bit RGB image as uint8 (H, W, 3)."""
    try:
        from PIL import Image  # noqa: WPS433
        with Image.open(path) as im:
            return np.asarray(im.convert("RGB"), dtype=np.uint8).copy()
    except ImportError:
        pass
    with tempfile.TemporaryDirectory() as tmp:
        ppm = os.path.join(tmp, "in.ppm")
        subprocess.run(["oiiotool", path, "--ch", "R,G,B", "-d", "uint8", "-o", ppm], check=True)
        data = open(ppm, "rb").read()
    # P6 header: magic, width, height, maxval, separated by whitespace (comments not written by oiiotool)
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        fields.append(data[start:pos])
    pos += 1
    if fields[0] != b"P6" or int(fields[3]) != 255:
        raise ValueError(f"{path}: unexpected PPM from oiiotool")
    w, h = int(fields[1]), int(fields[2])
    return np.frombuffer(data, dtype=np.uint8, count=w * h * 3, offset=pos).reshape(h, w, 3).copy()


def write_png(path, img):
    """uint8 (H, W, 3) as an 8-bit RGB PNG tagged sRGB (as the photos are)."""
    img = np.ascontiguousarray(img, dtype=np.uint8)
    h, w, _ = img.shape
    raw = np.zeros((h, 1 + w * 3), dtype=np.uint8)  # filter byte 0 per row
    raw[:, 1:] = img.reshape(h, w * 3)

    def chunk(tag, payload):
        return (struct.pack(">I", len(payload)) + tag + payload
                + struct.pack(">I", zlib.crc32(tag + payload) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)))
        f.write(chunk(b"sRGB", b"\x00"))
        f.write(chunk(b"IDAT", zlib.compress(raw.tobytes(), 6)))
        f.write(chunk(b"IEND", b""))


# ---------------------------------------------------------------- hashing

def hash3(i, j, k, seed):
    """uint32 hash of integer lattice coordinates (arrays), deterministic (lowbias32-style mix)."""
    with np.errstate(over="ignore"):  # uint32 arithmetic wraps on purpose
        x = (np.asarray(i, dtype=np.int64).astype(np.uint32) * np.uint32(0x8DA6B343)
             ^ np.asarray(j, dtype=np.int64).astype(np.uint32) * np.uint32(0xD8163841)
             ^ np.uint32(k) * np.uint32(0xCB1AB31F)
             ^ np.uint32(seed & 0xFFFFFFFF) * np.uint32(0x9E3779B9))
        x = x.astype(np.uint32)
        x ^= x >> np.uint32(16)
        x *= np.uint32(0x7FEB352D)
        x ^= x >> np.uint32(15)
        x *= np.uint32(0x846CA68B)
        x ^= x >> np.uint32(16)
        return x


# ---------------------------------------------------------------- minimum-error cut

def corner_cut(a, b, band):
    """Minimum-error cut between two (m, m, 3) float images over the upper-left quadrant of a
    tile (m = T/2): a is the 'N' role (pixels with x > y), b the 'W' role (x < y).
    The seam is a 4-connected path over anti-diagonals s = x + y = 0 .. 2m-2 with
    t = x - y, |t| <= min(band, s - 2 (s >= 2), 2m - 2 - s); pixels with t > k(s) come from a,
    t < k(s) from b, the seam pixel itself from a when k >= 0 else b.
    Returns (mask: True where a, cost: sum of the seam pixels' squared differences)."""
    m = a.shape[0]
    err = ((a - b) ** 2).sum(axis=2)  # (y, x)
    n_s = 2 * m - 1
    off = m - 1  # t in [-(m-1), m-1] -> index t + off
    inf = np.inf
    # e[s, t+off] for valid (s, t)
    s_idx = np.arange(n_s)[:, None]
    t_idx = np.arange(-off, off + 1)[None, :]
    x = (s_idx + t_idx)
    y = (s_idx - t_idx)
    parity_ok = (x % 2 == 0)
    x //= 2
    y //= 2
    inside = parity_ok & (x >= 0) & (y >= 0) & (x < m) & (y < m)
    lim = np.minimum(np.minimum(band, np.where(s_idx >= 2, s_idx - 2, s_idx)), 2 * m - 2 - s_idx)
    ok = inside & (np.abs(t_idx) <= lim)
    e = np.full((n_s, 2 * off + 1), inf)
    e[ok] = err[y[ok], x[ok]]
    d = np.full_like(e, inf)
    d[0] = e[0]
    back = np.zeros(e.shape, dtype=np.int8)
    for s in range(1, n_s):
        left = np.full(2 * off + 1, inf)   # from t-1
        right = np.full(2 * off + 1, inf)  # from t+1
        left[1:] = d[s - 1, :-1]
        right[:-1] = d[s - 1, 1:]
        take_right = right < left
        d[s] = e[s] + np.where(take_right, right, left)
        back[s] = np.where(take_right, 1, -1)
    # end: s = 2m-2 has the single pixel t = 0
    k = np.zeros(n_s, dtype=np.int64)
    k[-1] = 0
    cost = d[-1, off]
    if not np.isfinite(cost):
        raise RuntimeError("no feasible cut")
    for s in range(n_s - 1, 0, -1):
        k[s - 1] = k[s] + back[s, k[s] + off]
    # mask over the quadrant
    yy, xx = np.mgrid[0:m, 0:m]
    ss = xx + yy
    tt = xx - yy
    ks = k[ss]
    mask = (tt > ks) | ((tt == ks) & (ks >= 0))
    return mask, float(cost)


class TileSet:
    def __init__(self, photo, T, C, positions, band):
        self.T, self.C = T, C
        f = photo.astype(np.float64) / 255.0
        # samples: 0..C-1 horizontal-edge colours, C..2C-1 vertical-edge colours
        self.positions = positions
        self.samples = [photo[y:y + T, x:x + T] for (x, y) in positions]
        sf = [f[y:y + T, x:x + T] for (x, y) in positions]
        h = T // 2
        self.band = max(1, int(round(band * T)))
        # the parts of each sample each triangle sees, as (h, T) or (T, h) arrays
        # N role: tile rows 0..h-1 <- sample rows h..T-1; S role: tile rows h..T-1 <- rows 0..h-1
        # W role: tile cols 0..h-1 <- sample cols h..T-1; E role: tile cols h..T-1 <- cols 0..h-1
        self.cuts = {}
        self.cost = 0.0
        for hc in range(C):
            for vc in range(C):
                sh, sv = sf[hc], sf[C + vc]
                # quadrant views in tile coordinates
                N_ul, W_ul = sh[h:T, 0:h], sv[0:h, h:T]          # upper-left: N vs W
                N_ur, E_ur = sh[h:T, h:T], sv[0:h, 0:h]          # upper-right: N vs E
                S_ll, W_ll = sh[0:h, 0:h], sv[h:T, h:T]          # lower-left: S vs W
                S_lr, E_lr = sh[0:h, h:T], sv[h:T, 0:h]          # lower-right: S vs E
                # bring each quadrant to the upper-left form (corner at (0,0), a = vertical role)
                m, c = corner_cut(N_ul, W_ul, self.band)
                self.cuts[("NW", hc, vc)] = m
                self.cost += c
                m, c = corner_cut(N_ur[:, ::-1], E_ur[:, ::-1], self.band)
                self.cuts[("NE", hc, vc)] = m[:, ::-1]
                self.cost += c
                m, c = corner_cut(S_ll[::-1, :], W_ll[::-1, :], self.band)
                self.cuts[("SW", hc, vc)] = m[::-1, :]
                self.cost += c
                m, c = corner_cut(S_lr[::-1, ::-1], E_lr[::-1, ::-1], self.band)
                self.cuts[("SE", hc, vc)] = m[::-1, ::-1]
                self.cost += c
        self.tiles = np.zeros((C, C, C, C, T, T, 3), dtype=np.uint8)  # [N, E, S, W]
        for n in range(C):
            for e in range(C):
                for s in range(C):
                    for w in range(C):
                        self.tiles[n, e, s, w] = self._tile(n, e, s, w)

    def _tile(self, n, e, s, w):
        T, C, h = self.T, self.C, self.T // 2
        sn, ss = self.samples[n], self.samples[s]
        sw, se = self.samples[C + w], self.samples[C + e]
        t = np.empty((T, T, 3), dtype=np.uint8)
        # upper-left: N vs W
        m = self.cuts[("NW", n, w)][..., None]
        t[0:h, 0:h] = np.where(m, sn[h:T, 0:h], sw[0:h, h:T])
        m = self.cuts[("NE", n, e)][..., None]
        t[0:h, h:T] = np.where(m, sn[h:T, h:T], se[0:h, 0:h])
        m = self.cuts[("SW", s, w)][..., None]
        t[h:T, 0:h] = np.where(m, ss[0:h, 0:h], sw[h:T, h:T])
        m = self.cuts[("SE", s, e)][..., None]
        t[h:T, h:T] = np.where(m, ss[0:h, h:T], se[h:T, 0:h])
        return t

    def synthesise(self, W, H, seed):
        T, C = self.T, self.C
        ni, nj = (W + T - 1) // T, (H + T - 1) // T
        i = np.arange(ni + 1)[None, :]
        j = np.arange(nj + 1)[:, None]
        hcol = (hash3(i, j, 0, seed) % np.uint32(C)).astype(np.int64)  # [j, i]: top edge of cell (i, j)
        vcol = (hash3(i, j, 1, seed) % np.uint32(C)).astype(np.int64)  # [j, i]: left edge of cell (i, j)
        out = np.empty((nj * T, ni * T, 3), dtype=np.uint8)
        used = np.zeros((C, C, C, C), dtype=np.int64)
        for cj in range(nj):
            for ci in range(ni):
                n, s = hcol[cj, ci], hcol[cj + 1, ci]
                w, e = vcol[cj, ci], vcol[cj, ci + 1]
                used[n, e, s, w] += 1
                out[cj * T:(cj + 1) * T, ci * T:(ci + 1) * T] = self.tiles[n, e, s, w]
        return out[:H, :W], used


def choose_positions(rng, photo_w, photo_h, T, C, separation=0.0):
    """2C random T x T crops; with separation > 0, centres at least separation*T apart (L1:
    1 = the diamonds the tiles show do not overlap), by rejection (relaxed after 1000 tries)."""
    pos = []
    tries = 0
    while len(pos) < 2 * C:
        x = int(rng.integers(0, photo_w - T + 1))
        y = int(rng.integers(0, photo_h - T + 1))
        tries += 1
        need = separation * T * (0.9 ** (tries // 1000))
        if all(abs(x - px) + abs(y - py) >= need for px, py in pos):
            pos.append((x, y))
    return pos


def diamond_coverage(positions, T, photo_w, photo_h):
    """Fraction of the photo's pixels inside the union of the samples' diamonds (what tiles show)."""
    cov = np.zeros((photo_h, photo_w), dtype=bool)
    yy, xx = np.mgrid[0:T, 0:T]
    h = T / 2.0
    diamond = (np.abs(xx + 0.5 - h) + np.abs(yy + 0.5 - h)) <= h
    for (x, y) in positions:
        cov[y:y + T, x:x + T] |= diamond
    return cov.mean(), int(cov.sum())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("photo")
    ap.add_argument("out")
    ap.add_argument("-T", type=int, default=256, help="tile side, px (even)")
    ap.add_argument("-C", type=int, default=2, help="colours per edge direction (C^4 tiles)")
    ap.add_argument("-k", type=int, default=1, help="best of k random sample sets (least seam error)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--band", type=float, default=0.25,
                    help="cut band half-width as a fraction of T (anti-diagonal steps)")
    ap.add_argument("--separation", type=float, default=0.0,
                    help="min L1 distance between sample centres / T (1: the diamonds do not overlap)")
    ap.add_argument("--control", action="store_true",
                    help="control: paste one of the 2C samples whole per cell (hashed) instead of the tiles")
    ap.add_argument("--size", default=None, help="WxH of the synthesis (default: the photo's)")
    ap.add_argument("--side-by-side", default=None, help="PNG: photo | synthesis, no gap (halved while over 2048 px)")
    ap.add_argument("--atlas", default=None, help="PNG of the tile set (C^2 x C^2 tiles)")
    a = ap.parse_args()

    photo = read_png(a.photo)
    ph, pw, _ = photo.shape
    T, C = a.T, a.C
    if T % 2 or T > min(pw, ph) or T < 4:
        sys.exit(f"T must be even, >= 4 and <= {min(pw, ph)}")
    W, H = (pw, ph) if a.size is None else map(int, a.size.lower().split("x"))

    rng = np.random.default_rng(a.seed)
    best = None
    costs = []
    for _ in range(max(1, a.k)):
        pos = choose_positions(rng, pw, ph, T, C, a.separation)
        ts = TileSet(photo, T, C, pos, a.band)
        costs.append(ts.cost)
        if best is None or ts.cost < best.cost:
            best = ts
    ts = best
    img, used = ts.synthesise(W, H, a.seed)
    if a.control:
        # control: the same 2C samples, one whole sample per lattice cell (hashed), hard seams
        T_ = ts.T
        for cj in range((H + T_ - 1) // T_):
            for ci in range((W + T_ - 1) // T_):
                q = int(hash3(ci, cj, 2, a.seed) % np.uint32(2 * C))
                blk = img[cj * T_:(cj + 1) * T_, ci * T_:(ci + 1) * T_]
                blk[...] = ts.samples[q][:blk.shape[0], :blk.shape[1]]
        print("CONTROL: one whole sample per cell, no Wang tiles, no cuts")
    write_png(a.out, img)

    n_tiles = C ** 4
    tile_bytes = n_tiles * T * T * 3
    sample_bytes = 2 * C * T * T * 3
    cells = used.sum()
    cov_frac, cov_px = diamond_coverage(ts.positions, T, pw, ph)
    distinct_px = C * T * T  # 2C samples, each showing a diamond of T^2/2 px
    print(f"photo {a.photo} {pw}x{ph}; synthesis {a.out} {W}x{H}")
    print(f"T {T} C {C} k {a.k} seed {a.seed} band {ts.band} px separation {a.separation}")
    print(f"sample positions (x, y), horizontal colours then vertical: {ts.positions}")
    print(f"seam cost: chosen {ts.cost:.2f} (mean squared sRGB diff per seam pixel "
          f"{ts.cost / (4 * C * C * (T - 1)):.5f}); candidates {['%.2f' % c for c in costs]}")
    print(f"tiles {n_tiles}; lattice cells {cells}; tiles used {int((used > 0).sum())}; "
          f"max uses of one tile {int(used.max())}")
    print(f"tile-set bytes (8-bit RGB) {tile_bytes}")
    print(f"samples bytes (8-bit RGB, tiles rebuilt at load; cuts recomputed or {4 * C * C * (T - 1)} "
          f"seam steps at 1 bit) {sample_bytes}")
    print(f"distinct content: C*T^2 = {distinct_px} px = {distinct_px / (W * H):.3f} of the synthesis; "
          f"the samples' diamonds cover {cov_frac:.3f} of the photo ({cov_px} px)")

    if a.side_by_side:
        if img.shape[0] == ph:
            sbs = np.concatenate([photo, img], axis=1)
        else:
            sbs = img
        while sbs.shape[1] > 2048 or sbs.shape[0] > 2048:
            hh, ww = sbs.shape[0] // 2 * 2, sbs.shape[1] // 2 * 2
            sbs = sbs[:hh, :ww].reshape(hh // 2, 2, ww // 2, 2, 3).mean(axis=(1, 3)).round().astype(np.uint8)
        write_png(a.side_by_side, sbs)
    if a.atlas:
        g = C * C
        atlas = np.full((g * (T + 4), g * (T + 4), 3), 255, np.uint8)
        for idx, (n, e, s, w) in enumerate(np.ndindex(C, C, C, C)):
            r, c = divmod(idx, g)
            atlas[r * (T + 4):r * (T + 4) + T, c * (T + 4):c * (T + 4) + T] = ts.tiles[n, e, s, w]
        write_png(a.atlas, atlas)


if __name__ == "__main__":
    main()
