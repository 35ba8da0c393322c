// Shared snippet: the original's maths made total. Wherever the original is defined these return
// exactly what it returns; where it is not (normalize of a zero vector, pow(0, 0), a negative
// exponent) they return a finite value instead of NaN or infinity.

// normalize(v), or the zero vector for a zero vector (GLSL leaves that undefined: NaN on llvmpipe).
vec3 safe_normalize(vec3 v) {
    return dot(v, v) > 0.0 ? normalize(v) : vec3(0.0);
}

// pow(x, y) for x >= 0: 0 where x is 0 (no reflection towards the eye; llvmpipe's pow gives the
// same, GLSL leaves pow(0, y <= 0) undefined) and negative exponents treated as 0 (the original
// would blow up towards infinity near the terminator).
float safe_pow(float x, float y) {
    return x > 0.0 ? pow(x, max(y, 0.0)) : 0.0;
}
