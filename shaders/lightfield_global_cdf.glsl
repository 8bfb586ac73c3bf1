// The box functions of lightfield_balanced.glsl for the precomputed global CDFs (Fig. 11's
// baseline): every image's box is the whole image, weighted by all its energy, and sampled by its
// global CDF, whatever the receiver can see.
bool lfBox(int m, vec3 q, out vec2 a, out vec2 b) {
    a = lfImageMin();
    b = lfImageMax();
    return true;
}
float lfBoxWeight(int m, vec2 a, vec2 b) { return lfTotal(m); }
bool lfDraw(int m, vec2 a, vec2 b, vec2 xi, float Am, out vec2 sp, out float scale) {
    scale = 1.0;
    return lfSampleBox(m, a, b, xi, sp);
}
