#include "gpu/imgui_layer.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <GLFW/glfw3.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "gpu/key_taps.h"

namespace tallow::gpu {
namespace {

/// The panel's font: DejaVu Sans (Debian's fonts-dejavu-core) when installed, for the units and
/// help texts' σ, ε, mm⁻¹, ², →, –; Dear ImGui's built-in font (ASCII and Latin-1 only) otherwise.
constexpr const char* kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
constexpr float kFontPixels = 15.0f;
/// Latin-1, Greek, general punctuation, super- and subscripts, arrows, mathematical operators.
constexpr ImWchar kGlyphRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2000, 0x206F, 0x2070, 0x209F,
                                    0x2190, 0x21FF, 0x2200, 0x22FF, 0};

void loadFont(ImGuiIO& io) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(kFontFile, ec)) return;
  io.Fonts->AddFontFromFileTTF(kFontFile, kFontPixels, nullptr, kGlyphRanges);
}

/// One layer at a time (one window): its taps, the backend's key callback it wraps, the keys held.
KeyTaps* activeTaps = nullptr;
GLFWkeyfun backendKeyCallback = nullptr;
std::vector<int> heldTaps;

/// The modifiers as the backend sets them from the keys' state (it does so only in its key callback).
void updateModifiers(ImGuiIO& io) {
  io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
  io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
  io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
  io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
}

/// The backend's callback first (it passes the key on to the one installed before it: the hotkeys),
/// then the press remembered.
void onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  if (backendKeyCallback) backendKeyCallback(window, key, scancode, action, mods);
  if (activeTaps && action == GLFW_PRESS && key >= 0 && key < IM_ARRAYSIZE(ImGuiIO::KeysDown)) activeTaps->pressed(key);
}

}  // namespace

ImGuiLayer::ImGuiLayer(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in the user's folder: the panel starts the same every time
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  loadFont(io);
  if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) {
    ImGui::DestroyContext();
    throw std::runtime_error("imgui: the GLFW backend did not start");
  }
  // GLSL 4.10 core and above select the backend's 410 shaders; our context is 4.5 core.
  if (!ImGui_ImplOpenGL3_Init("#version 450 core")) {
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    throw std::runtime_error("imgui: the OpenGL 3 backend did not start");
  }
  window_ = window;
  activeTaps = &taps_;
  backendKeyCallback = glfwSetKeyCallback(window, onKey);
}

ImGuiLayer::~ImGuiLayer() {
  glfwSetKeyCallback(window_, backendKeyCallback);  // the backend restores the one before it
  activeTaps = nullptr;
  backendKeyCallback = nullptr;
  heldTaps.clear();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::beginFrame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  // A key tapped between two frames is down for this one (gpu/key_taps.h).
  ImGuiIO& io = ImGui::GetIO();
  heldTaps = taps_.tapsToHold([&io](int key) { return io.KeysDown[key]; });
  for (const int key : heldTaps) io.KeysDown[key] = true;
  if (!heldTaps.empty()) updateModifiers(io);  // a tapped Ctrl-Z is Ctrl and Z for the frame
  ImGui::NewFrame();
}

void ImGuiLayer::endFrame() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  ImGuiIO& io = ImGui::GetIO();
  for (const int key : heldTaps) io.KeysDown[key] = false;  // released after its one frame
  if (!heldTaps.empty()) updateModifiers(io);
  heldTaps.clear();
}

bool ImGuiLayer::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace tallow::gpu
