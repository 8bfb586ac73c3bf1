#include "ui/KeyLatch.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace candela::ui {

namespace {

bool validKey(int key) {
    return key >= 0 && key < int(IM_ARRAYSIZE(ImGuiIO::KeysDown));
}

}  // namespace

void KeyLatch::install(GLFWwindow* window) {
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, &KeyLatch::onKey);
}

void KeyLatch::onKey(GLFWwindow* window, int key, int, int action, int mods) {
    auto* latch = static_cast<KeyLatch*>(glfwGetWindowUserPointer(window));
    if (latch && action == GLFW_PRESS && validKey(key)) latch->mPressed.emplace_back(key, mods);
}

void KeyLatch::apply(GLFWwindow* window) {
    ImGuiIO& io = ImGui::GetIO();
    // Keys held for one frame go back to their real state.
    for (int key : mHeld) io.KeysDown[key] = glfwGetKey(window, key) == GLFW_PRESS;
    mHeld.clear();
    // The backend's own modifier rule, applied to the restored keys.
    io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
    io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
    io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
    io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
    for (const auto& [key, mods] : mPressed) {
        if (!io.KeysDown[key]) {
            io.KeysDown[key] = true;
            mHeld.push_back(key);
        }
        io.KeyCtrl = io.KeyCtrl || (mods & GLFW_MOD_CONTROL);
        io.KeyShift = io.KeyShift || (mods & GLFW_MOD_SHIFT);
        io.KeyAlt = io.KeyAlt || (mods & GLFW_MOD_ALT);
        io.KeySuper = io.KeySuper || (mods & GLFW_MOD_SUPER);
    }
    mPressed.clear();
}

}  // namespace candela::ui
