#!/usr/bin/python3
"""Issue 33 experiment: tiling and blending (Heitz-Neyret, Sigma w^2 = 1, histogram-preserving
Gaussianisation, a periodic centred crop as the exemplar) with a dominant-tile selection by the
tiles' own values -- Mikkelsen's luminance-weighted selection ("bright": w_i ~ B_i^gamma exp(beta L_i),
the brighter tile wins) and a variant ("extreme": exp(beta |L_i|), the more contrasted tile wins),
L the tile's Gaussianised luma, the weights then L2-normalised. The model does not have it (weights
that depend on the tiles' values are non-linear in them, which the moment pre-filtering cannot
carry), so it is measured here first: score the output with `stex compare PHOTO OUT.png`.
Works on the photo's 8-bit sRGB values; the crop's own histogram (not the whole photo's), so W1 is
not comparable with the model's, structure and spectra are.

    /usr/bin/python3 scripts/luminance-selection-experiment.py PHOTO OUT.png EXEMPLAR_SIDE GAMMA BETA bright|extreme SEED
"""
import sys, numpy as np
from PIL import Image
from scipy.special import ndtri
from scipy.stats import norm

def periodic(u):  # Moisan's periodic component, per channel
    h, w = u.shape
    v = np.zeros_like(u)
    v[0, :] += u[-1, :] - u[0, :]; v[-1, :] += u[0, :] - u[-1, :]
    v[:, 0] += u[:, -1] - u[:, 0]; v[:, -1] += u[:, 0] - u[:, -1]
    q = np.arange(h)[:, None]; r = np.arange(w)[None, :]
    den = 2 * np.cos(2 * np.pi * q / h) + 2 * np.cos(2 * np.pi * r / w) - 4
    den[0, 0] = 1
    s = np.fft.fft2(v) / den; s[0, 0] = 0
    return u - np.real(np.fft.ifft2(s))

def gaussianise(c):
    ranks = np.argsort(np.argsort(c.ravel()))
    g = ndtri((ranks + 0.5) / ranks.size).reshape(c.shape)
    return g, np.sort(c.ravel())

def main():
    photo, out, size, gamma, beta, mode, seed = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]), sys.argv[6], int(sys.argv[7])
    img = np.asarray(Image.open(photo).convert("RGB"), dtype=np.float64) / 255
    H, W, _ = img.shape
    y0, x0 = (H - size) // 2, (W - size) // 2
    ex = np.stack([periodic(img[y0:y0 + size, x0:x0 + size, c]) for c in range(3)], -1)
    G, Q = [], []
    for c in range(3):
        g, q = gaussianise(ex[..., c]); G.append(g); Q.append(q)
    G = np.stack(G, -1)
    luma = G @ np.array([0.2126, 0.7152, 0.0722]); luma = (luma - luma.mean()) / luma.std()
    edge = 0.28867513 * size
    ys, xs = np.mgrid[0:H, 0:W].astype(np.float64)
    # skewed triangle lattice (Heitz-Neyret): uv = M^-1 p / edge
    u = (xs - ys / np.sqrt(3)) / edge; v = (2 * ys / np.sqrt(3)) / edge
    iu, iv = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
    fu, fv = u - iu, v - iv
    upper = fu + fv > 1
    verts = [(np.where(upper, iu + 1, iu), np.where(upper, iv + 1, iv)), (iu + 1, iv), (iu, iv + 1)]
    B = [np.where(upper, fu + fv - 1, 1 - fu - fv), np.where(upper, 1 - fv, fu), np.where(upper, 1 - fu, fv)]
    def h(a, b, k):
        x = (a * 73856093 ^ b * 19349663 ^ (seed * 83492791 + k)) & 0xffffffff
        x = (x ^ (x >> 16)) * 0x45d9f3b & 0xffffffff; x = (x ^ (x >> 16)) * 0x45d9f3b & 0xffffffff
        return (x ^ (x >> 16)) % size
    vals, lums, ws = [], [], []
    for (a, b), Bi in zip(verts, B):
        ox, oy = h(a, b, 1), h(a, b, 2)
        px = (xs.astype(np.int64) + ox) % size; py = (ys.astype(np.int64) + oy) % size
        vals.append(G[py, px]); lums.append(luma[py, px]); ws.append(np.maximum(Bi, 0) ** gamma)
    if beta > 0:
        for i in range(3):
            sel = lums[i] if mode == "bright" else np.abs(lums[i])  # "bright": the brighter tile wins; "extreme": the more extreme
            ws[i] = ws[i] * np.exp(beta * sel)
    norm2 = np.sqrt(sum(w * w for w in ws)) + 1e-12
    out_g = sum((w / norm2)[..., None] * val for w, val in zip(ws, vals))
    res = np.empty_like(out_g)
    for c in range(3):
        # Q o Phi: back to the exemplar's own values (the histogram-preserving map)
        p = norm.cdf(out_g[..., c]); res[..., c] = np.interp(p, (np.arange(size * size) + 0.5) / (size * size), Q[c])
    Image.fromarray(np.clip(res * 255 + 0.5, 0, 255).astype(np.uint8)).save(out)

main()
