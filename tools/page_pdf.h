#pragma once
// A report page (report.html) printed to PDF by headless Chromium (Debian's `chromium`: `--headless
// --print-to-pdf`, its own print layout of the page's @page A4 rule, no header or footer). Written to a
// temporary file beside the target and renamed, so a failed run leaves no partial PDF.

#include <filesystem>

namespace curette {

// False (and nothing written) when no `chromium` is on PATH; throws SystemError when it fails.
bool printPageToPdf(const std::filesystem::path& html, const std::filesystem::path& pdf);

}  // namespace curette
