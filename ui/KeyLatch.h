#pragma once
// Keeps quick key taps from getting lost. Dear ImGui 1.86 reads keys as "down when the frame
// starts", so a key pressed and released between two frames (a tap during a slow progressive
// frame on a software GPU, or synthetic input) never reaches it. The latch records presses from
// the GLFW key callback and holds each tapped key, with the modifiers held at the time, down for
// one ImGui frame, as the GLFW backend already does for mouse buttons.

#include <utility>
#include <vector>

struct GLFWwindow;

namespace candela::ui {

class KeyLatch {
  public:
    /// Installs the key callback; call before ImGui_ImplGlfw_InitForOpenGL, which chains to it.
    /// Uses the window's user pointer.
    void install(GLFWwindow* window);
    /// Call between ImGui_ImplGlfw_NewFrame() and ImGui::NewFrame().
    void apply(GLFWwindow* window);

  private:
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

    std::vector<std::pair<int, int>> mPressed;  ///< (key, modifier bits) pressed since last frame.
    std::vector<int> mHeld;                     ///< Keys this latch forced down last frame.
};

}  // namespace candela::ui
