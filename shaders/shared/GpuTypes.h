// Structs and constants shared by C++ and GLSL (std430 / std140 layouts, vec4-aligned only: no
// bool and no bare vec3 in buffers). Included from C++ via this header and from GLSL through the
// shader loader's #include. Sizes are checked by static_assert in renderer/GpuLayout.cpp.
#ifdef __cplusplus
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
namespace candela::gpu {
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using uvec4 = glm::uvec4;
using ivec4 = glm::ivec4;
#define CANDELA_CONST static constexpr
#else
#define CANDELA_CONST const
#endif

/// Material flags stored in the G-buffer's albedo.w.
CANDELA_CONST int kMaterialGlossy = 1;
CANDELA_CONST int kMaterialEmitter = 2;

/// G-buffer attachments, in binding order.
CANDELA_CONST int kGBufferPosition = 0;  // xyz world position (m), w = 1 where a surface was hit
CANDELA_CONST int kGBufferNormal = 1;    // xyz unit shading normal, w = Phong exponent
CANDELA_CONST int kGBufferAlbedo = 2;    // rgb diffuse albedo, w = material flags
CANDELA_CONST int kGBufferSpecular = 3;  // rgb glossy reflectance, w unused
CANDELA_CONST int kGBufferEmission = 4;  // rgb emitted radiance towards the camera, W/(m2 sr)
CANDELA_CONST int kGBufferCount = 5;

/// Buffer binding points.
CANDELA_CONST int kBindingFrame = 0;      // UBO FrameUniforms
CANDELA_CONST int kBindingLuminaire = 1;  // SSBO of the luminaire kind's records
CANDELA_CONST int kBindingBvhNodes = 2;   // SSBO BvhNode[]
CANDELA_CONST int kBindingBvhTris = 3;    // SSBO BvhTriangle[]
CANDELA_CONST int kBindingTestIn = 6;     // SSBOs of parity and chi-square compute tests
CANDELA_CONST int kBindingTestOut = 7;
CANDELA_CONST int kBindingEnvCube = 8;  // SSBO vec2 per cube texel: luminance x solid angle, weight
CANDELA_CONST int kBindingEnvFaces = 11;    // SSBO EnvironmentFaceGpu[6]
CANDELA_CONST int kBindingEnvSamples = 12;  // SSBO EnvironmentSampleGpu[6][pool]
CANDELA_CONST int kBindingEnvExtra = 13;    // SSBO of Havran lights

/// The environment's CDFs as textures (float-float pairs, RG32F; environment_cdf.comp writes
/// them through image units, shading reads them with texelFetch): CDF(v | u) of face f, column c
/// in row c of layer f, N + 1 entries; CDF(u) of face f in row f of the column table, N + 1
/// entries, and the columns' totals in row 6 + f. The global-cdf technique's lat-long CDF (RG32F,
/// built on the CPU): row 0 the CDF over rows, row 1 + y the CDF over row y's columns, entry i in
/// .r of texel i - 1 (entry 0 is 0, so a map 16384 texels wide fits GL's 16384), the line's
/// search guide in .g (cdfSearchGuide in renderer/passes/EnvironmentPass.h).
CANDELA_CONST int kUnitEnvRowCdf = 11;
CANDELA_CONST int kUnitEnvColumnCdf = 12;
CANDELA_CONST int kUnitEnvGlobalCdf = 13;  // RG32F: the lat-long CDF and its search guide (.g)
CANDELA_CONST int kImageEnvRowCdf = 0;
CANDELA_CONST int kImageEnvColumnCdf = 1;

/// Shadow maps of the luminaire being shaded (renderer/passes/ShadowMapPass.h): the header and
/// one ShadowMapGpu per map at kBindingShadowMaps, the shares at kBindingShadowShares (vec2
/// (map, weight) per item and share, items x dims.z), the depth cube maps (6 layers per map,
/// samplerCubeArrayShadow) on texture unit kUnitShadowMaps.
/// Texture units of a luminaire's tables (luminaires/GpuTable.h): 2D arrays read with texelFetch.
/// A light field's summed-area tables (RG32F float-float pairs, one layer per image), luminance
/// (R32F), colour ratios (RGBA16F) and granier2003's far-field ratios (R32F, size x size per
/// image); a photometric file's intensity table (R32F, vertical angle along x, horizontal along y)
/// and its cells' CDF (R32F, entry k at (k mod (nv - 1), k div (nv - 1)); (nv-1)(nh-1)+1 entries
/// from 0 to 1). Kinds never share a program, so their units may coincide.
CANDELA_CONST int kUnitLightFieldSat = 8;
CANDELA_CONST int kUnitLightFieldLum = 9;
CANDELA_CONST int kUnitLightFieldColour = 10;
CANDELA_CONST int kUnitLightFieldGranier = 11;
CANDELA_CONST int kUnitPhotometricIntensity = 8;
CANDELA_CONST int kUnitPhotometricCellCdf = 9;

CANDELA_CONST int kBindingShadowMaps = 14;
CANDELA_CONST int kBindingShadowShares = 15;
CANDELA_CONST int kUnitShadowMaps = 6;
struct ShadowMapsGpu {
    ivec4 dims;   // x = maps, y = face resolution (texels), z = shares per item, w unused
    vec4 params;  // x = near, y = far (m); z = normal offset, w = depth offset (texels)
};
/// Directional shadow maps (one per Havran light): at kBindingDirectionalShadowMaps the header
/// (dims.x = maps, dims.y = resolution; params.x = texel size (m), params.y = the bounding
/// sphere's radius, params.zw = the offsets in texels) and one world-to-clip mat4 per map
/// (orthographic); the depth maps (sampler2DArrayShadow) on kUnitDirectionalShadowMaps.
CANDELA_CONST int kBindingDirectionalShadowMaps = 16;
CANDELA_CONST int kUnitDirectionalShadowMaps = 7;
struct ShadowMapGpu {
    vec4 light;  // xyz world position of the map's light (m); w = 1 if rendered
};

/// Texture unit of the lat-long environment map (RGB32F, intensity applied, row 0 = top, v = 0).
CANDELA_CONST int kUnitEnvironmentMap = 5;

/// Cube-map sampling weights (luminaires/environment/EnvironmentSampling.h, CubeMapDistribution):
/// the share of the largest luminance a texel touches, and the floor as a fraction of the face's
/// mean.
CANDELA_CONST float kEnvMaxShare = 0.1;
CANDELA_CONST float kEnvFaceFloor = 1e-3;
/// Steps along each edge of a cube texel at which the largest luminance it may touch is sought
/// in the lat-long map (touchedMaximum: steps + 1 points per edge).
CANDELA_CONST int kEnvTouchedSteps = 16;

/// Per-frame constants (std140 UBO).
struct FrameUniforms {
    mat4 viewProj;     // world -> clip
    mat4 invViewProj;  // clip -> world
    vec4 cameraPos;    // xyz metres
    ivec4 frameInfo;   // x = frame index (sample batch), y = samples per pixel per frame,
                       // z = luminaire index being shaded, w = 1 if shadows are traced
    vec4 viewport;     // xy size in pixels, zw = 1/size
    ivec4 seeds;       // x = seed of this accumulation's random numbers, yzw unused
};

/// A Lambertian rectangle: corner, edge vectors, radiance (std430).
struct LambertianRectGpu {
    vec4 corner;    // xyz metres; w = area m2
    vec4 edgeX;     // xyz full width along c0 (m); w = width
    vec4 edgeY;     // xyz full height along aim x c0 (m); w = height
    vec4 radiance;  // rgb W/(m2 sr) emitted to the +aim side; w unused
    vec4 normal;    // xyz unit aim; w unused
};

/// A light-field luminaire (std430): this header, then in the same buffer the summed-area
/// tables of all images as float-float pairs (vec2, shaders/ff.glsl), their luminance as floats
/// and, for RGB data, their colour ratios as two packed halves per pixel
/// (luminaires/lightfield/LightFieldLuminaire.cpp packs it). Offsets are in elements of each
/// array's type from the start of the buffer.
struct LightFieldGpu {
    vec4 position;  // xyz world position of the local origin (m)
    vec4 axisX;     // xyz world direction of local +x (c0)
    vec4 axisY;     // xyz world direction of local +y
    vec4 axisZ;     // xyz world direction of local +z (aim)
    vec4 geometry;  // x = delta (m), yz = basis spacing (m), w = 1 for the goesele model
    vec4 origin;    // xy = basis node (0,0) on U (m), zw = image min on S (m)
    vec4 image;     // xy = image max on S (m), zw = pixel size (m)
    vec4 grid;      // xy = image min - origin.zw (m), zw = 1 / pixel size (1/m): with
                    // origin.zw and gridLow.xy, float-float pairs for the exact pixel grid
    vec4 gridLow;   // xy = 1 / pixel size - grid.zw (1/m), zw unused
    ivec4 dims;     // x, y = basis count W, H; z, w = image width, height (pixels)
    ivec4 offsets;  // x, y, z unused (the images are textures: GpuTable.h), w = 1 if RGB
    ivec4 options;  // x = K_max samples per image per frame (0: no cap), y = offset of
                    // granier2003's grid (floats: min.xy, max.xy of its centres on S; its ratios
                    // at kUnitLightFieldGranier), z = its size, w unused
};

/// A photometric area light (std430): this header, then in the same buffer as floats the
/// vertical angles (radians), the horizontal angles (radians), the candela table (scale
/// applied, [h * vertical + v]) and the opening polygon's corners (x, y pairs, metres, local
/// z = 0, counter-clockwise about +z). Offsets are in floats from the start of the buffer.
struct PhotometricGpu {
    vec4 position;  // xyz world centre of the opening (m); w = opening area (m2)
    vec4 axisX;     // xyz world direction of local +x (C0); w = largest opening extent (m)
    vec4 axisY;     // xyz world direction of local +y (C90); w = tilted-horizon epsilon (m)
    vec4 axisZ;     // xyz world direction of local +z (aim, gamma = 0); w unused
    vec4 colour;    // rgb tint; w = scale (dimming), applied to the candela texture
    ivec4 dims;     // x = vertical count, y = horizontal count, z = polygon corners (0: point,
                    // 2: segment), w = 1 for type B goniometry
    ivec4 offsets;  // x = vertical angles, y = horizontal angles, z unused (the candela table is
                    // the texture at kUnitPhotometricIntensity), w = polygon
    ivec4 samples;  // x, y = offsets of the 24- and 40-point Poisson sets (x, y pairs in the
                    // unit square), z = 1 when the table's cell CDF for the reference's
                    // intensity-proportional directions is bound (kUnitPhotometricCellCdf;
                    // 0: none, a table of zeros), w unused
};

/// Per-frame state of the environment passes (std140 UBO at kBindingEnvironment).
CANDELA_CONST int kBindingEnvironment = 4;
struct EnvironmentGpu {
    ivec4 dims;   // x, y = lat-long width, height; z = cube face size N; w = samples per face
                  // in the pool
    vec4 params;  // x = rotation about +Y (rad); y = 1 to show the map behind the scene; zw unused
    ivec4 frame;  // x = seed of this frame's light samples; y = supersampling k; zw unused
    ivec4 extra;  // x = count of Havran lights or 0; yzw unused
};

/// One cube face's totals (std430).
struct EnvironmentFaceGpu {
    vec4 totals;  // x = I_f, the face's total sampling weight; y = sum of luminance x solid
                  // angle (the face's energy); zw unused
};

/// A light sample of one face drawn before shading (Algorithm 1, line 10), std430.
struct EnvironmentSampleGpu {
    vec4 direction;  // xyz unit direction; w = pdf_L(w | f), 1/sr (0: no sample)
    vec4 radiance;   // rgb radiance of the map along it; w unused
};

/// Most inner levels on any root-to-leaf path of the BVH (Bvh::kMaxDepth): the GLSL traversal
/// stack holds one more entry.
CANDELA_CONST int kBvhMaxDepth = 31;

/// BVH node (std430): bounds with the child or triangle range packed in w as int bits.
struct BvhNode {
    vec4 lo;  // xyz min; w = intBitsToFloat(first child index, or first triangle if leaf)
    vec4 hi;  // xyz max; w = intBitsToFloat(triangle count; 0 for an inner node)
};

/// Triangle as vertex plus two edges (std430).
struct BvhTriangle {
    vec4 v0;
    vec4 e1;
    vec4 e2;
};

#ifdef __cplusplus
}  // namespace candela::gpu
#endif
