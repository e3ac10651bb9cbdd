#include "view/detail/site.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "view/view_errors.hpp"

namespace sculpt::view::detail {

std::filesystem::path three_directory(const std::filesystem::path& given) {
  if (!given.empty()) return given;
  if (const char* dir = std::getenv("SCULPT_THREE_DIR"); dir && *dir) return dir;
  return "/usr/share/javascript/three";
}

Site load_site(const std::filesystem::path& three_dir) {
  // The UMD builds of r111 (Debian 12's libjs-three): each script adds to the global THREE.
  static constexpr const char* kFiles[][2] = {
      {"/three/three.min.js", "build/three.min.js"},
      {"/three/OrbitControls.js", "examples/js/controls/OrbitControls.js"},
  };
  Site site;
  site.page = page_html();
  for (const auto& [url, relative] : kFiles) {
    const std::filesystem::path path = three_dir / relative;
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in || text.str().empty())
      throw ViewError("three.js is missing: cannot read " + path.string() +
                      " (install Debian's libjs-three: apt-get install libjs-three; or set SCULPT_THREE_DIR to "
                      "a folder with build/three.min.js and examples/js/controls/OrbitControls.js)");
    site.scripts[url] = text.str();
  }
  return site;
}

}  // namespace sculpt::view::detail
