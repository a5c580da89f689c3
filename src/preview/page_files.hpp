// The preview's page (src/preview/page/*.html, *.js, *.css), embedded at build time by
// cmake/embed_files.cmake.
#pragma once
#include <string>
#include <vector>

namespace penink {

struct PageFile {
    std::string name;  // file name, e.g. "preview.js"
    std::string text;
};

const std::vector<PageFile>& preview_page_files();

// The text of the embedded file `name`; throws std::out_of_range when there is none.
const std::string& preview_page_file(const std::string& name);

}  // namespace penink
