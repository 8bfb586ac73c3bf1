#include <cstdio>
#include <filesystem>

#include "app/commands/Commands.h"
#include "luminaires/Registry.h"
#include "scene/GltfLoader.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {

static void printMeshes(const Scene& scene) {
    size_t triangles = 0;
    for (const Mesh& m : scene.meshes) triangles += m.triangleCount();
    std::printf("meshes: %zu (%zu triangles), materials: %zu\n", scene.meshes.size(), triangles,
                scene.materials.size());
    for (const Mesh& m : scene.meshes) {
        const Material& mat = scene.materials.at(m.material);
        std::printf("  mesh \"%s\": %zu triangles, material \"%s\" albedo (%.3g, %.3g, %.3g)%s\n",
                    m.name.c_str(), m.triangleCount(), mat.name.c_str(), mat.albedo.x, mat.albedo.y,
                    mat.albedo.z, mat.isGlossy() ? ", glossy" : "");
    }
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    std::printf("bounds: (%.3f, %.3f, %.3f) .. (%.3f, %.3f, %.3f) m\n", lo.x, lo.y, lo.z, hi.x,
                hi.y, hi.z);
}

int cmdInfo(const Args& args) {
    if (args.size() != 1) throw InputError("usage: candela info FILE (.json scene, .gltf, .glb)");
    const std::string& path = args[0];
    std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".json") {
        Scene scene = loadScene(path);
        std::printf("scene: %s\n", path.c_str());
        std::printf("geometry entries: %zu\n", scene.geometry.size());
        printMeshes(scene);
        std::printf("luminaires: %zu\n", scene.luminaires.size());
        for (const auto& l : scene.luminaires) {
            const TechniqueInfo* t = findTechnique(l->kind(), l->technique);
            glm::dvec3 p = l->pose.position;
            std::printf("  \"%s\": %s\n    at (%.3f, %.3f, %.3f) m, technique %s (%s)\n",
                        l->name.c_str(), l->describe().c_str(), p.x, p.y, p.z,
                        l->technique.c_str(), t ? std::string(t->description).c_str() : "?");
        }
        std::printf("environment: %s\n", scene.environment.is_null() ? "none" : scene.environment.dump().c_str());
        const Camera& c = scene.camera;
        std::printf("camera: at (%.3f, %.3f, %.3f) m looking at (%.3f, %.3f, %.3f) m, fov %.1f deg\n",
                    c.position.x, c.position.y, c.position.z, c.target.x, c.target.y, c.target.z,
                    c.fovDeg);
        return 0;
    }
    if (ext == ".gltf" || ext == ".glb") {
        Scene scene;
        loadGltf(path, glm::dmat4(1.0), scene, json::Where{path, ""});
        std::printf("glTF: %s\n", path.c_str());
        printMeshes(scene);
        return 0;
    }
    throw InputError(path + ": unsupported file type \"" + ext + "\" (expected .json, .gltf or .glb)");
}

}  // namespace candela
