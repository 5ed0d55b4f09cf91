// tallow_xkeys: presses keys in an X window, for the view's window tests — as a user's fingers
// would, each a tap (press and release at once), which a program that polls key states once a
// frame misses at low frame rates.
//   tallow_xkeys TITLE TIMEOUT_S KEY[:PAUSE_MS]...
// waits up to TIMEOUT_S for a top-level window whose name contains TITLE, then for each KEY (an X
// keysym name: space, Escape, F1, Right, z; "ctrl+z" holds Control; "wait" sends nothing) sends a
// KeyPress and a KeyRelease to it, then waits PAUSE_MS (default 200). Exit 0 when every key was sent; 1 when the
// window never appeared; 2 on bad arguments.
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

namespace {

/// The window's _NET_WM_NAME (UTF-8, as GLFW sets it; WM_NAME of a title beyond Latin-1, such as
/// "Tallow — blob", is compound text, which XFetchName does not return).
std::string windowName(Display* display, Window w) {
  const Atom netName = XInternAtom(display, "_NET_WM_NAME", False), utf8 = XInternAtom(display, "UTF8_STRING", False);
  Atom type = 0;
  int format = 0;
  unsigned long items = 0, after = 0;
  unsigned char* data = nullptr;
  std::string name;
  if (XGetWindowProperty(display, w, netName, 0, 1024, False, utf8, &type, &format, &items, &after, &data) == Success &&
      data) {
    name.assign(reinterpret_cast<const char*>(data), items);
    XFree(data);
  }
  return name;
}

/// The first window under `w` (depth first) whose name contains `title`; 0 if none.
Window findWindow(Display* display, Window w, const char* title) {
  if (windowName(display, w).find(title) != std::string::npos) return w;
  Window root = 0, parent = 0, *children = nullptr;
  unsigned count = 0;
  if (!XQueryTree(display, w, &root, &parent, &children, &count)) return 0;
  Window found = 0;
  for (unsigned i = 0; i < count && !found; ++i) found = findWindow(display, children[i], title);
  if (children) XFree(children);
  return found;
}

void send(Display* display, Window window, int type, KeyCode code, unsigned state) {
  XKeyEvent e{};
  e.type = type;
  e.display = display;
  e.window = window;
  e.root = DefaultRootWindow(display);
  e.subwindow = None;
  e.time = CurrentTime;
  e.same_screen = True;
  e.keycode = code;
  e.state = state;
  XSendEvent(display, window, True, type == KeyPress ? KeyPressMask : KeyReleaseMask, reinterpret_cast<XEvent*>(&e));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: tallow_xkeys TITLE TIMEOUT_S KEY[:PAUSE_MS]...\n");
    return 2;
  }
  Display* display = XOpenDisplay(nullptr);
  if (!display) {
    std::fprintf(stderr, "tallow_xkeys: cannot open the display\n");
    return 1;
  }
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(std::atoi(argv[2]));
  Window window = 0;
  while (!(window = findWindow(display, DefaultRootWindow(display), argv[1]))) {
    if (std::chrono::steady_clock::now() > end) {
      std::fprintf(stderr, "tallow_xkeys: no window named \"%s\"\n", argv[1]);
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (int i = 3; i < argc; ++i) {
    std::string key = argv[i];
    int pauseMs = 200;
    if (const auto colon = key.find(':'); colon != std::string::npos) {
      pauseMs = std::atoi(key.c_str() + colon + 1);
      key.resize(colon);
    }
    if (key == "wait") {
      std::this_thread::sleep_for(std::chrono::milliseconds(pauseMs));
      continue;
    }
    unsigned state = 0;
    if (key.rfind("ctrl+", 0) == 0) {
      state = ControlMask;
      key = key.substr(5);
    }
    const KeySym sym = XStringToKeysym(key.c_str());
    const KeyCode code = sym == NoSymbol ? 0 : XKeysymToKeycode(display, sym);
    if (!code) {
      std::fprintf(stderr, "tallow_xkeys: unknown key \"%s\"\n", key.c_str());
      return 2;
    }
    send(display, window, KeyPress, code, state);
    send(display, window, KeyRelease, code, state);
    XFlush(display);
    std::this_thread::sleep_for(std::chrono::milliseconds(pauseMs));
  }
  XCloseDisplay(display);
  return 0;
}
