#pragma once
/// \file site.hpp
/// What the view's server serves (internal): its own page and three files of Debian's
/// libjs-three, read once when the server starts. Nothing else is ever served.

#include <filesystem>
#include <map>
#include <string>

namespace sculpt::view::detail {

struct Site {
  std::string page;                            ///< the page (HTML with its script), at "/"
  std::map<std::string, std::string> scripts;  ///< URL path ("/three/three.min.js") -> file contents
};

/// The page compiled into the library (lib/view/page/view.html).
const std::string& page_html();

/// The folder of three.js: `given` if not empty, else $SCULPT_THREE_DIR, else
/// /usr/share/javascript/three (Debian's libjs-three).
std::filesystem::path three_directory(const std::filesystem::path& given);

/// Reads the page and the three.js files from `three_dir`.
/// \throw ViewError naming the missing file and the package that provides it.
Site load_site(const std::filesystem::path& three_dir);

}  // namespace sculpt::view::detail
