// Alpha to coverage that means the same on every driver: a fragment of alpha a covers, of the
// pixel's N samples, floor(N a + ξ) — ξ uniform in 0 … 1, so a share a on average — at a
// rotation of its own. Mesa's built-in alpha-to-coverage (llvmpipe) rounds N a up without a
// dither and gives every fragment in a pixel the same samples: blades' partly covered texels
// far away (minified tips, fading LOD) covered up to half a sample more than their alpha, and
// overlapping ones hid one another instead of adding up. ξ and the rotation come from a hash of
// the pixel and the fragment's `salt` (its triangle, or cell), so overlapping blades pick their
// samples independently, as the blades they stand for cover a pixel independently (not
// gl_PrimitiveID, which takes llvmpipe off its fast path).
#if defined FRAGMENT_SHADER
uint coverage_hash(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
    return v.x ^ v.y ^ v.z;
}

int coverage_mask(float alpha, uint salt) {
    int n = gl_NumSamples;
    if (n <= 1) return ~0;  // one sample: the alpha test alone, as alpha-to-coverage does
    uint h = coverage_hash(uvec3(uvec2(gl_FragCoord.xy), salt));
    float xi = float(h & 0xFFFFu) / 65536.0;
    int k = clamp(int(floor(clamp(alpha, 0.0, 1.0) * float(n) + xi)), 0, n);
    int full = (1 << n) - 1;
    int bits = (1 << k) - 1;
    int r = int((h >> 16u) % uint(n));
    return ((bits << r) | (bits >> (n - r))) & full;
}
#endif
