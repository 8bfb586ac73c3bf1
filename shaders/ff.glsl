// Float-float numbers: a vec2 (hi, lo) standing for hi + lo with |lo| <= ulp(hi) / 2, about 48
// significant bits from fp32 operations alone (Dekker 1971; Knuth's TwoSum). Sums that must
// carry more digits than a float (summed-area tables, CDFs of maps with a sun 1e8 times brighter
// than the sky) are stored and combined as these, so that no shader needs fp64, which consumer GPUs
// run at 1/32 to 1/64 of the fp32 rate and some drivers lack.
//
// The error-free transformations depend on the exact order of float operations: every
// intermediate is `precise`, which forbids the compiler to reassociate or fuse them (GLSL 4.50,
// 4.7.1). The tables are written by C++ (splitting a 64-bit value into two floats) or by
// environment_cdf.comp.

/// a + b exactly, as the rounded sum and its error (Knuth's TwoSum; no ordering needed).
vec2 ffTwoSum(float a, float b) {
    precise float s = a + b;
    precise float bb = s - a;
    precise float e = (a - (s - bb)) + (b - bb);
    return vec2(s, e);
}

/// a + b exactly for |a| >= |b| (or a = 0) (Dekker's FastTwoSum): renormalises a pair.
vec2 ffFastTwoSum(float a, float b) {
    precise float s = a + b;
    precise float e = b - (s - a);
    return vec2(s, e);
}

/// a + b, with an error of about 2^-47 of |a| + |b| (the "sloppy" float-float sum: under
/// cancellation the error is relative to the operands, as a 64-bit subtraction's would be).
vec2 ffAdd(vec2 a, vec2 b) {
    vec2 s = ffTwoSum(a.x, b.x);
    precise float lo = s.y + (a.y + b.y);
    return ffFastTwoSum(s.x, lo);
}

vec2 ffSub(vec2 a, vec2 b) { return ffAdd(a, -b); }

/// a + b for a float b.
vec2 ffAddF(vec2 a, float b) {
    vec2 s = ffTwoSum(a.x, b);
    precise float lo = s.y + a.y;
    return ffFastTwoSum(s.x, lo);
}

/// a as the sum of two floats of 12 significant bits each (Veltkamp's split), whose products are
/// exact in float. Valid for |a| below about 8e34.
vec2 ffSplit(float a) {
    precise float c = 4097.0 * a;
    precise float hi = c - (c - a);
    precise float lo = a - hi;
    return vec2(hi, lo);
}

/// a x b exactly, as the rounded product and its error (Dekker's TwoProduct). Not fma: drivers
/// may lower fma to a multiply and an add (Mesa's llvmpipe does), which loses the error.
vec2 ffTwoProduct(float a, float b) {
    precise float p = a * b;
    vec2 x = ffSplit(a), y = ffSplit(b);
    precise float e = ((x.x * y.x - p) + x.x * y.y + x.y * y.x) + x.y * y.y;
    return vec2(p, e);
}

/// a x b for a float b.
vec2 ffMulF(vec2 a, float b) {
    vec2 p = ffTwoProduct(a.x, b);
    precise float lo = p.y + a.y * b;
    return ffFastTwoSum(p.x, lo);
}

/// a x b, to about 2^-46 relative.
vec2 ffMul(vec2 a, vec2 b) {
    vec2 p = ffTwoProduct(a.x, b.x);
    precise float lo = p.y + (a.x * b.y + a.y * b.x);
    return ffFastTwoSum(p.x, lo);
}

/// a / b, to about 2^-46 relative (one Newton correction of the float quotient).
vec2 ffDiv(vec2 a, vec2 b) {
    float q = a.x / b.x;
    vec2 r = ffSub(a, ffMulF(b, q));
    return ffFastTwoSum(q, r.x / b.x);
}

/// The nearest float.
float ffToFloat(vec2 a) { return a.x + a.y; }

/// a - b rounded to float once (ffToFloat(ffSub(a, b)) without renormalising the pair).
float ffSubToFloat(vec2 a, vec2 b) {
    vec2 s = ffTwoSum(a.x, -b.x);
    precise float lo = s.y + (a.y - b.y);
    return s.x + lo;
}

/// a <= b for normalised pairs (each hi the nearest float of hi + lo).
bool ffLessEqual(vec2 a, vec2 b) { return a.x < b.x || (a.x == b.x && a.y <= b.y); }
