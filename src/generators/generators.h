#pragma once
// Procedural volumes with known geometry, for the demo, tests and analytic ground truth.
// Spec: gen:NAME[:N], N the edge length in samples (default 64, at least 2). All are N×N×N
// float32 volumes (their native type: the values are not whole numbers) with values in [0, 1]
// and spacing 1.
//
// Formulas, in voxel coordinates p = (x, y, z) with x, y, z in 0..N-1 (sample centres) and the
// centre c = ((N-1)/2, (N-1)/2, (N-1)/2). clamp01(t) = min(max(t, 0), 1).
//
//  sphere          f = clamp01(1 - r / (N/2)),  r = |p - c|.
//                  The iso-surface f = v is the sphere of radius (1 - v)·N/2 around c.
//
//  cube            f = clamp01(1 - d / (N/2)),  d = max(|x - c.x|, |y - c.y|, |z - c.z|): Rautek et
//                  al.'s Figure 6, a cube whose density increases towards its centre (the
//                  fig6-cube rule preset). The iso-surface f = v is the cube of half side
//                  (1 - v)·N/2 around c.
//
//  spheres         Two Gaussian blobs that melt into one ("melted spheres", Nagy–Klein Fig. 3):
//                  g(q) = exp(-|p - q|² / (2σ²)), σ = N/8, centres a,b = c ∓ (N/6, 0, 0),
//                  f = clamp01((g(a) + g(b)) / (1 + exp(-(N/3)² / (2σ²)))),
//                  i.e. normalized to 1 at each centre (the sum peaks slightly above 1 between
//                  them; that sliver is clamped). On the x axis midway, f = 2e^(-8/9)/(1+e^(-32/9))
//                  ≈ 0.7994, so the iso 0.5 surface is one blob with a saddle waist of radius
//                  σ·sqrt(2 ln(0.7994/0.5)) ≈ 0.121·N in the plane x = c.x.
//
//  torus           d = distance of p to the circle of radius R = N/4 around c in the plane
//                  z = c.z:  d = sqrt((sqrt((x-c.x)² + (y-c.y)²) - R)² + (z-c.z)²),
//                  f = clamp01(1 - d / (N/8)). The iso-surface f = v is a tube of radius
//                  (1 - v)·N/8 around that circle: iso 0.5 gives tube radius N/16.
//
//  marschner-lobb  The Marschner–Lobb test signal (f_M = 6, α = 0.25) on [-1, 1]³:
//                  u = -1 + 2p/(N-1) per axis, ρ(r) = cos(2π f_M cos(π r / 2)),
//                  f = (1 - sin(π u_z / 2) + α (1 + ρ(sqrt(u_x² + u_y²)))) / (2 (1 + α)),
//                  which lies in [0, 1] by construction (no further mapping).
//
//  hydrogen        The magnitude of the hydrogen 3d_z² orbital, normalized to a peak of 1:
//                  q = p - c, r = |q|, a = N/48 (Bohr radius in voxels),
//                  f = |3 q_z² - r²| · exp(-r / (3a)) / (72 a² e^-2).
//                  (|ψ|, i.e. the density with a gamma of 1/2, so both features stay usable.)
//                  Two lobes along ±z peak at f = 1 at r = 6a = N/8; a ring in the plane
//                  z = c.z peaks at f = 0.5 at the same radius; f = 0 on the cones
//                  3 cos²θ = 1 and at c.
//
//  blobs           Eight Gaussian blobs, f = min(1, Σ_k A_k exp(-|p - m_k|² / (2 s_k²))), with
//                  parameters drawn from std::mt19937 seeded 20240607 (its output is fixed by
//                  the C++ standard): u() = (draw >> 8) · 2^-24 in [0, 1); per blob, in this
//                  order, m_k = N·(0.25 + 0.5 u()) for x, y, z, s_k = N·(1/24 + (1/10 - 1/24)u()),
//                  A_k = 0.5 + 0.5 u(). Deterministic for a given N.
#include <string>
#include <vector>

#include "core/volume.h"

namespace vsil {

std::vector<std::string> generatorNames();
// `spec` without the "gen:" prefix, e.g. "sphere:128". Throws InputError (naming the spec and
// listing the valid names) for an unknown name or a bad N; N is checked against `limits`.
// The result's name is NAME and its source "gen:NAME:N". With a `region` (--crop, --stride)
// only its samples are computed, as a file of the whole volume read with that region holds.
Volume generateVolume(const std::string& spec, const VolumeLimits& limits = {},
                      const ReadRegion& region = {});

}  // namespace vsil
