// Deterministic per-pixel random numbers (PCG hash, O'Neill 2014 / Jarzynski & Olano 2020), so a jittered
// image is the same on every run and the CPU reference can reproduce it (render/reference/random.h).
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1) from a pixel and a seed.
float pixelRandom(uvec2 pixel, uint seed) {
    return float(pcgHash(pixel.x ^ pcgHash(pixel.y ^ pcgHash(seed))) >> 8u) * (1.0 / 16777216.0);
}
