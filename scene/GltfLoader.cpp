#include "scene/GltfLoader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>

#include "util/Activity.h"
#include "util/Error.h"
#include "util/FileInput.h"

namespace candela {

namespace {

/// Roughness below which a glTF material keeps a glossy lobe. Rougher materials are treated as
/// purely diffuse (specular 0): their lobe is so wide that a Lambertian term carries the look,
/// and the renderer then skips glossy shading for them.
constexpr double kGlossyRoughnessLimit = 0.6;
/// Normal-incidence reflectance of a dielectric in the metallic-roughness model.
constexpr double kDielectricF0 = 0.04;

int componentBytes(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return 8;
        default:
            return 0;
    }
}

int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
        default:
            return 0;
    }
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A checked window on an accessor's bytes: element i starts at data + i * stride and holds
/// `components` values of `componentType`, all inside the buffer.
struct AccessorView {
    const unsigned char* data = nullptr;
    size_t count = 0;
    size_t stride = 0;
    int componentType = 0;
    int components = 0;
};

/// Converts one file's model into Candela meshes; every failure throws InputError(prefix: ...).
class GltfImport {
  public:
    GltfImport(const tinygltf::Model& model, std::string prefix, Scene& scene)
        : mModel(model),
          mPrefix(std::move(prefix)),
          mScene(scene),
          mVisited(model.nodes.size(), false) {}

    void run(const glm::dmat4& transform);

  private:
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(mPrefix + ": " + what);
    }
    void warn(const std::string& what) const {
        std::fprintf(stderr, "warning: %s: %s\n", mPrefix.c_str(), what.c_str());
    }

    AccessorView view(int accessorIndex, const std::string& what) const;
    std::vector<glm::vec3> readFloat3(int accessorIndex, const std::string& what) const;
    std::vector<uint32_t> readIndices(int accessorIndex, size_t vertexCount,
                                      const std::string& what) const;
    glm::dmat4 localTransform(const tinygltf::Node& node, int index) const;
    void visitNode(int index, const glm::dmat4& parent);
    /// Transforms p to world space; fails when the result is not finite.
    glm::vec3 worldPoint(const glm::dmat4& toWorld, const glm::vec3& p,
                         const std::string& what) const;
    /// The primitive's triangle list: its indices, or 0..vertexCount-1 when it has none.
    std::vector<uint32_t> primitiveIndices(const tinygltf::Primitive& primitive, size_t vertexCount,
                                           const std::string& what) const;
    /// The file's vertices and normals in world space; zero normals take a face's.
    void addSmoothVertices(Mesh& mesh, const std::vector<glm::vec3>& positions,
                           const std::vector<glm::vec3>& normals,
                           const std::vector<uint32_t>& indices, const glm::dmat4& toWorld,
                           bool mirrored, const std::string& what) const;
    /// Three vertices of its own per triangle, with the face normal (flat shading).
    void addFlatTriangles(Mesh& mesh, const std::vector<glm::vec3>& positions,
                          const std::vector<uint32_t>& indices, const glm::dmat4& toWorld,
                          bool mirrored, const std::string& what) const;
    void addPrimitive(const tinygltf::Primitive& primitive, const std::string& name,
                      const glm::dmat4& toWorld);
    uint32_t material(int index);
    glm::dvec3 textureMeanLinear(int textureIndex);

    const tinygltf::Model& mModel;
    std::string mPrefix;
    Scene& mScene;
    std::vector<bool> mVisited;
    std::map<int, uint32_t> mMaterials;  ///< glTF material index -> Scene::materials index.
};

AccessorView GltfImport::view(int accessorIndex, const std::string& what) const {
    const std::string name = what + " (accessor " + std::to_string(accessorIndex) + ")";
    if (accessorIndex < 0 || size_t(accessorIndex) >= mModel.accessors.size())
        fail(what + ": accessor index " + std::to_string(accessorIndex) + " is out of range");
    const tinygltf::Accessor& accessor = mModel.accessors[size_t(accessorIndex)];
    if (accessor.sparse.isSparse) fail(name + ": sparse accessors are not supported");
    if (accessor.bufferView < 0 || size_t(accessor.bufferView) >= mModel.bufferViews.size())
        fail(name + ": bufferView " + std::to_string(accessor.bufferView) + " is out of range");
    const tinygltf::BufferView& bufferView = mModel.bufferViews[size_t(accessor.bufferView)];
    if (bufferView.buffer < 0 || size_t(bufferView.buffer) >= mModel.buffers.size())
        fail(name + ": buffer " + std::to_string(bufferView.buffer) + " is out of range");
    const std::vector<unsigned char>& buffer = mModel.buffers[size_t(bufferView.buffer)].data;
    if (bufferView.byteLength > buffer.size() ||
        bufferView.byteOffset > buffer.size() - bufferView.byteLength) {
        fail(name + ": bufferView " + std::to_string(accessor.bufferView) + " (bytes " +
             std::to_string(bufferView.byteOffset) + " + " + std::to_string(bufferView.byteLength) +
             ") lies outside its buffer of " + std::to_string(buffer.size()) +
             " bytes (truncated .bin?)");
    }
    AccessorView out;
    out.componentType = accessor.componentType;
    out.components = componentCount(accessor.type);
    size_t elementBytes = size_t(componentBytes(accessor.componentType)) * size_t(out.components);
    if (elementBytes == 0) fail(name + ": invalid component type or element type");
    out.stride = bufferView.byteStride ? bufferView.byteStride : elementBytes;
    if (out.stride < elementBytes)
        fail(name + ": byteStride " + std::to_string(out.stride) + " is smaller than an element");
    out.count = accessor.count;
    if (out.count == 0) return out;
    // The last element must end inside the bufferView (written to avoid size_t overflow).
    size_t available = bufferView.byteLength;
    if (accessor.byteOffset > available || available - accessor.byteOffset < elementBytes ||
        (out.count - 1) > (available - accessor.byteOffset - elementBytes) / out.stride) {
        fail(name + ": " + std::to_string(out.count) + " elements at offset " +
             std::to_string(accessor.byteOffset) + " do not fit in bufferView " +
             std::to_string(accessor.bufferView) + " of " + std::to_string(available) +
             " bytes (accessor out of range)");
    }
    out.data = buffer.data() + bufferView.byteOffset + accessor.byteOffset;
    return out;
}

std::vector<glm::vec3> GltfImport::readFloat3(int accessorIndex, const std::string& what) const {
    AccessorView v = view(accessorIndex, what);
    if (v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || v.components != 3) {
        fail(what + " (accessor " + std::to_string(accessorIndex) +
             "): expected float VEC3 data (quantised or non-float attributes are not supported)");
    }
    std::vector<glm::vec3> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        float xyz[3];
        std::memcpy(xyz, v.data + i * v.stride, sizeof xyz);
        out[i] = glm::vec3(xyz[0], xyz[1], xyz[2]);
        if (!finite(glm::dvec3(out[i])))
            fail(what + ": element " + std::to_string(i) + " is not finite");
    }
    return out;
}

std::vector<uint32_t> GltfImport::readIndices(int accessorIndex, size_t vertexCount,
                                              const std::string& what) const {
    AccessorView v = view(accessorIndex, what);
    int bytes = componentBytes(v.componentType);
    bool unsignedType = v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                        v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                        v.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    if (v.components != 1 || !unsignedType)
        fail(what + ": indices must be unsigned 8, 16 or 32-bit scalars");
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        const unsigned char* p = v.data + i * v.stride;
        uint32_t index = 0;
        if (bytes == 1) {
            index = p[0];
        } else if (bytes == 2) {
            uint16_t s;
            std::memcpy(&s, p, 2);
            index = s;
        } else {
            std::memcpy(&index, p, 4);
        }
        if (index >= vertexCount) {
            fail(what + ": index " + std::to_string(index) + " at position " + std::to_string(i) +
                 " is out of range (" + std::to_string(vertexCount) + " vertices)");
        }
        out[i] = index;
    }
    return out;
}

glm::dmat4 GltfImport::localTransform(const tinygltf::Node& node, int index) const {
    const std::string where = "node " + std::to_string(index);
    auto checkFinite = [&](const std::vector<double>& values, const char* field) {
        for (double x : values)
            if (!std::isfinite(x)) fail(where + ": " + field + " is not finite");
    };
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(where + ": matrix must have 16 numbers");
        checkFinite(node.matrix, "matrix");
        return glm::make_mat4(node.matrix.data());  // glTF matrices are column-major, as glm.
    }
    glm::dmat4 m(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) fail(where + ": translation must have 3 numbers");
        checkFinite(node.translation, "translation");
        m = glm::translate(m, glm::make_vec3(node.translation.data()));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) fail(where + ": rotation must have 4 numbers");
        checkFinite(node.rotation, "rotation");
        const std::vector<double>& r = node.rotation;  // glTF order: x, y, z, w.
        glm::dquat q(r[3], r[0], r[1], r[2]);
        if (glm::length(q) < 1e-12) fail(where + ": rotation is a zero quaternion");
        m *= glm::mat4_cast(glm::normalize(q));
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) fail(where + ": scale must have 3 numbers");
        checkFinite(node.scale, "scale");
        m = glm::scale(m, glm::make_vec3(node.scale.data()));
    }
    return m;
}

void GltfImport::visitNode(int index, const glm::dmat4& parent) {
    if (index < 0 || size_t(index) >= mModel.nodes.size())
        fail("node index " + std::to_string(index) + " is out of range");
    if (mVisited[size_t(index)])
        fail("node " + std::to_string(index) + " is reached twice (the node graph must be a tree)");
    mVisited[size_t(index)] = true;
    const tinygltf::Node& node = mModel.nodes[size_t(index)];
    glm::dmat4 toWorld = parent * localTransform(node, index);
    if (node.mesh >= 0) {
        if (size_t(node.mesh) >= mModel.meshes.size())
            fail("node " + std::to_string(index) + ": mesh " + std::to_string(node.mesh) +
                 " is out of range");
        const tinygltf::Mesh& mesh = mModel.meshes[size_t(node.mesh)];
        std::string base = !node.name.empty()   ? node.name
                           : !mesh.name.empty() ? mesh.name
                                                : "mesh " + std::to_string(node.mesh);
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            std::string name = mesh.primitives.size() == 1 ? base : base + "/" + std::to_string(p);
            addPrimitive(mesh.primitives[p], name, toWorld);
        }
    }
    for (int child : node.children) visitNode(child, toWorld);
}

/// Unit normal of the triangle (a, b, c) by its winding; +y for a degenerate one.
glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
    double length = glm::length(n);
    return length > 0.0 ? glm::vec3(n / length) : glm::vec3(0.f, 1.f, 0.f);
}

glm::vec3 GltfImport::worldPoint(const glm::dmat4& toWorld, const glm::vec3& p,
                                 const std::string& what) const {
    glm::dvec3 w = glm::dvec3(toWorld * glm::dvec4(glm::dvec3(p), 1.0));
    if (!finite(w)) fail(what + ": transformed position is not finite");
    // A finite double can still leave float's range (a translation of 2e97 m, found by fuzzing:
    // the vertex became inf): refuse what the renderer cannot hold.
    glm::vec3 out(w);
    if (!finite(glm::dvec3(out)))
        fail(what +
             ": transformed position beyond single precision's range (about 3e38 m); check the "
             "node's transform");
    return out;
}

std::vector<uint32_t> GltfImport::primitiveIndices(const tinygltf::Primitive& primitive,
                                                   size_t vertexCount,
                                                   const std::string& what) const {
    std::vector<uint32_t> indices;
    if (primitive.indices >= 0) {
        indices = readIndices(primitive.indices, vertexCount, what + " indices");
        if (indices.size() % 3 != 0)
            fail(what + ": index count " + std::to_string(indices.size()) +
                 " is not a multiple of 3");
    } else {
        if (vertexCount % 3 != 0)
            fail(what + ": vertex count " + std::to_string(vertexCount) +
                 " is not a multiple of 3");
        for (uint32_t i = 0; i < vertexCount; ++i) indices.push_back(i);
    }
    return indices;
}

void GltfImport::addSmoothVertices(Mesh& mesh, const std::vector<glm::vec3>& positions,
                                   const std::vector<glm::vec3>& normals,
                                   const std::vector<uint32_t>& indices, const glm::dmat4& toWorld,
                                   bool mirrored, const std::string& what) const {
    glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(toWorld)));
    for (size_t i = 0; i < positions.size(); ++i) {
        mesh.positions.push_back(worldPoint(toWorld, positions[i], what));
        glm::dvec3 n = normalMatrix * glm::dvec3(normals[i]);
        double length = glm::length(n);
        mesh.normals.push_back(length > 1e-12 && std::isfinite(length) ? glm::vec3(n / length)
                                                                       : glm::vec3(0.f));
    }
    mesh.indices = indices;
    // Zero-length normals in the file get the normal of a face that uses the vertex.
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t* tri = &indices[t];
        for (int k = 0; k < 3; ++k) {
            if (mesh.normals[tri[k]] != glm::vec3(0.f)) continue;
            glm::vec3 face =
                faceNormal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
            mesh.normals[tri[k]] = mirrored ? -face : face;
        }
    }
}

void GltfImport::addFlatTriangles(Mesh& mesh, const std::vector<glm::vec3>& positions,
                                  const std::vector<uint32_t>& indices, const glm::dmat4& toWorld,
                                  bool mirrored, const std::string& what) const {
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        glm::vec3 a = worldPoint(toWorld, positions[indices[t]], what);
        glm::vec3 b = worldPoint(toWorld, positions[indices[t + 1]], what);
        glm::vec3 c = worldPoint(toWorld, positions[indices[t + 2]], what);
        glm::vec3 n = mirrored ? -faceNormal(a, b, c) : faceNormal(a, b, c);
        for (const glm::vec3& p : {a, b, c}) {
            mesh.indices.push_back(uint32_t(mesh.positions.size()));
            mesh.positions.push_back(p);
            mesh.normals.push_back(n);
        }
    }
}

void GltfImport::addPrimitive(const tinygltf::Primitive& primitive, const std::string& name,
                              const glm::dmat4& toWorld) {
    const std::string what = "mesh \"" + name + "\"";
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        warn(what + ": primitive mode " + std::to_string(primitive.mode) +
             " is not a triangle list; skipped");
        return;
    }
    auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(what + ": primitive has no POSITION");
    std::vector<glm::vec3> positions = readFloat3(position->second, what + " POSITION");
    std::vector<uint32_t> indices = primitiveIndices(primitive, positions.size(), what);

    Mesh mesh;
    mesh.name = name;
    mesh.shape = MeshShape::General;
    mesh.material = material(primitive.material);
    glm::dmat3 linear(toWorld);
    bool mirrored = glm::determinant(linear) < 0.0;  // Keeps triangles counter-clockwise.
    auto normal = primitive.attributes.find("NORMAL");
    if (normal != primitive.attributes.end()) {
        std::vector<glm::vec3> normals = readFloat3(normal->second, what + " NORMAL");
        if (normals.size() != positions.size())
            fail(what + ": NORMAL count " + std::to_string(normals.size()) +
                 " differs from POSITION count " + std::to_string(positions.size()));
        addSmoothVertices(mesh, positions, normals, indices, toWorld, mirrored, what);
    } else {
        // No normals: flat shading, three vertices of its own per triangle.
        addFlatTriangles(mesh, positions, indices, toWorld, mirrored, what);
    }
    if (mirrored)
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    mesh.computeBounds();
    mScene.meshes.push_back(std::move(mesh));
}

uint32_t GltfImport::material(int index) {
    auto cached = mMaterials.find(index);
    if (cached != mMaterials.end()) return cached->second;

    Material out;
    if (index < 0) {
        out.name = "default";  // No glTF material: Candela's default grey.
    } else {
        if (size_t(index) >= mModel.materials.size())
            fail("material " + std::to_string(index) + " is out of range");
        const tinygltf::Material& m = mModel.materials[size_t(index)];
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        out.name = m.name.empty() ? "material " + std::to_string(index) : m.name;
        if (pbr.baseColorFactor.size() < 3)
            fail("material \"" + out.name + "\": baseColorFactor needs 4 numbers");
        glm::dvec3 base(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
        if (!finite(base)) fail("material \"" + out.name + "\": baseColorFactor is not finite");
        if (pbr.baseColorTexture.index >= 0) base *= textureMeanLinear(pbr.baseColorTexture.index);
        base = glm::clamp(base, 0.0, 1.0);
        double metallic =
            std::clamp(std::isfinite(pbr.metallicFactor) ? pbr.metallicFactor : 0.0, 0.0, 1.0);
        double roughness =
            std::clamp(std::isfinite(pbr.roughnessFactor) ? pbr.roughnessFactor : 1.0, 0.0, 1.0);
        // The metallicRoughness texture is not read: factors only.
        out.roughness = float(roughness);
        if (roughness < kGlossyRoughnessLimit) {
            out.albedo = glm::vec3(base * (1.0 - metallic));
            out.specular = glm::vec3(glm::mix(glm::dvec3(kDielectricF0), base, metallic));
        } else {
            // Treated as diffuse (see kGlossyRoughnessLimit); rough metals keep their colour.
            out.albedo = glm::vec3(base);
            out.specular = glm::vec3(0.f);
        }
        // emissiveFactor is ignored: emissive surfaces load as ordinary surfaces, because
        // Candela's light comes only from its explicit luminaires (scene "luminaires").
    }
    mScene.materials.push_back(out);
    uint32_t sceneIndex = uint32_t(mScene.materials.size() - 1);
    mMaterials[index] = sceneIndex;
    return sceneIndex;
}

glm::dvec3 GltfImport::textureMeanLinear(int textureIndex) {
    const std::string what = "texture " + std::to_string(textureIndex);
    if (size_t(textureIndex) >= mModel.textures.size()) fail(what + " is out of range");
    int source = mModel.textures[size_t(textureIndex)].source;
    if (source < 0 || size_t(source) >= mModel.images.size()) {
        warn(what + " has no usable image; its colour is taken as white");
        return glm::dvec3(1.0);
    }
    const tinygltf::Image& image = mModel.images[size_t(source)];
    size_t bytesPerValue = image.bits == 16 ? 2 : image.bits == 8 ? 1 : 0;
    size_t pixels =
        image.width > 0 && image.height > 0 ? size_t(image.width) * size_t(image.height) : 0;
    size_t channels = image.component > 0 && image.component <= 4 ? size_t(image.component) : 0;
    if (pixels == 0 || channels == 0 || bytesPerValue == 0 ||
        image.image.size() < pixels * channels * bytesPerValue) {
        warn("image \"" + image.uri + "\" was not decoded; its colour is taken as white");
        return glm::dvec3(1.0);
    }
    // Mean in linear space: sRGB-encoded texels are decoded before averaging.
    std::array<double, 256> lut8;
    for (int i = 0; i < 256; ++i) lut8[size_t(i)] = srgbToLinear(i / 255.0);
    glm::dvec3 sum(0.0);
    const unsigned char* data = image.image.data();
    for (size_t p = 0; p < pixels; ++p) {
        glm::dvec3 c;
        for (size_t k = 0; k < 3; ++k) {
            size_t channel = channels >= 3 ? k : 0;  // Grey (+alpha) images: replicate.
            size_t at = (p * channels + channel) * bytesPerValue;
            if (bytesPerValue == 1) {
                c[int(k)] = lut8[data[at]];
            } else {
                uint16_t v;
                std::memcpy(&v, data + at, 2);
                c[int(k)] = srgbToLinear(v / 65535.0);
            }
        }
        sum += c;
    }
    return sum / double(pixels);
}

void GltfImport::run(const glm::dmat4& transform) {
    for (const std::string& extension : mModel.extensionsRequired)
        fail("requires the glTF extension \"" + extension + "\", which Candela does not support");
    if (!mModel.scenes.empty()) {
        int sceneIndex = mModel.defaultScene >= 0 ? mModel.defaultScene : 0;
        if (size_t(sceneIndex) >= mModel.scenes.size())
            fail("default scene " + std::to_string(sceneIndex) + " is out of range");
        for (int node : mModel.scenes[size_t(sceneIndex)].nodes) visitNode(node, transform);
        return;
    }
    // No scene: every node that is nobody's child is a root.
    std::vector<bool> isChild(mModel.nodes.size(), false);
    for (const tinygltf::Node& node : mModel.nodes)
        for (int child : node.children)
            if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
    for (size_t i = 0; i < mModel.nodes.size(); ++i)
        if (!isChild[i]) visitNode(int(i), transform);
}

/// A URI's %XX escapes decoded (glTF file names with spaces are written %20).
std::string percentDecoded(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace

std::vector<std::string> loadGltf(const std::string& path, const glm::dmat4& transform,
                                  Scene& scene, const json::Where& where) {
    const std::string prefix = where.file.empty() ? path : where.str() + ": " + path;
    ScopedActivity activity("reading the glTF model " + prefix);
    try {
        checkInputFile(path, "glTF", kMaxGltfBytes);
    } catch (const InputError& e) {
        // The message names the path; the scene's field goes before it.
        throw InputError(where.file.empty() ? std::string(e.what())
                                            : where.str() + ": " + e.what());
    }

    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext != ".gltf" && ext != ".glb")
        throw InputError(prefix + ": unsupported file type \"" + ext +
                         "\" (expected .gltf or .glb)");

    tinygltf::TinyGLTF loader;
    // Every file tinygltf reads (the glTF, its buffers and images) through util/FileInput.h:
    // regular files only, each within kMaxGltfBytes (its own reader would block on a FIFO and
    // read a device until memory ran out).
    tinygltf::FsCallbacks reads{};
    reads.FileExists = [](const std::string& file, void*) {
        std::error_code ec;
        return std::filesystem::exists(file, ec);
    };
    reads.ExpandFilePath = [](const std::string& file, void*) { return file; };
    reads.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err,
                             const std::string& file, void*) {
        try {
            std::string bytes = readInputFile(file, "glTF", kMaxGltfBytes);
            out->assign(bytes.begin(), bytes.end());
            return true;
        } catch (const InputError& e) {
            if (err) *err += std::string(e.what()) + "\n";
            return false;
        }
    };
    reads.WriteWholeFile = [](std::string* err, const std::string&,
                              const std::vector<unsigned char>&, void*) {
        if (err) *err += "Candela does not write glTF files here\n";
        return false;
    };
    loader.SetFsCallbacks(reads);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                            : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    auto trim = [](std::string s) {
        while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
        return s;
    };
    if (!ok) {
        std::string detail = trim(err);
        if (!trim(warn).empty()) detail += (detail.empty() ? "" : "; ") + trim(warn);
        throw InputError(prefix + ": invalid glTF (" + (detail.empty() ? "unknown error" : detail) +
                         ")");
    }
    if (!trim(warn).empty())
        std::fprintf(stderr, "warning: %s: %s\n", prefix.c_str(), trim(warn).c_str());

    // A failure half-way removes what this file had added, leaving `scene` as it was.
    size_t materialCount = scene.materials.size(), meshCount = scene.meshes.size();
    try {
        GltfImport(model, prefix, scene).run(transform);
    } catch (...) {
        scene.materials.erase(scene.materials.begin() + std::ptrdiff_t(materialCount),
                              scene.materials.end());
        scene.meshes.erase(scene.meshes.begin() + std::ptrdiff_t(meshCount), scene.meshes.end());
        throw;
    }
    std::vector<std::string> files{path};
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    auto addUri = [&](const std::string& uri) {
        if (uri.empty() || uri.rfind("data:", 0) == 0) return;  // a .glb chunk or embedded data
        std::filesystem::path file(percentDecoded(uri));
        files.push_back((file.is_absolute() ? file : dir / file).string());
    };
    for (const tinygltf::Buffer& buffer : model.buffers) addUri(buffer.uri);
    for (const tinygltf::Image& image : model.images) addUri(image.uri);
    return files;
}

}  // namespace candela
