// The face-balanced estimator (Eq. 4-5 of Lu et al. 2013) shared by balanced, balanced-integer
// and uniform-faces: N_f = mu_f N_s fractional samples per face, the last one weighted by
// beta = frac(N_f). The technique's shader defines, before including this file,
//   void envFaceShares(Surface s, int ns, out float mu[6])   the proportions mu_f.
// The light samples are the pools drawn before shading (environment_cdf.comp, PASS_SAMPLES),
// shared by all pixels; each pixel starts at a random place in each pool (the interleaving the
// paper suggests against its spatial bias), so its estimate is unbiased and neighbours' errors
// are not all alike.
vec3 shadeTechnique(Surface s, int ns, inout uint rng) {
    vec3 result = vec3(0.0);
    float mu[6];
    envFaceShares(s, ns, mu);
    for (int f = 0; f < 6; ++f) {
        float nf = mu[f] * float(ns);  // N_f(n), fractional (Eq. 4)
        if (!(nf > 0.0)) continue;
        int count = int(ceil(nf));
        int start = int(rand01(rng) * float(env.dims.w));
        for (int i = 0; i < count; ++i) {
            float beta = float(i + 1) <= nf ? 1.0 : nf - floor(nf);  // Eq. (5)
            EnvironmentSampleGpu smp = poolSample(f, start, i);
            float pdf = smp.direction.w;
            if (!(pdf > 0.0)) continue;
            result += beta * integrand(s, smp.direction.xyz, smp.radiance.rgb) / (mu[f] * pdf);
        }
    }
    result /= float(ns);
    return result;
}
