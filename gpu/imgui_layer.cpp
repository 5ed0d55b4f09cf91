#include "gpu/imgui_layer.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <filesystem>
#include <stdexcept>

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
}

ImGuiLayer::~ImGuiLayer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::beginFrame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::endFrame() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool ImGuiLayer::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace tallow::gpu
