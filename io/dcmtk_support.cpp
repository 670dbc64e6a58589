#include "io/dcmtk_support.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/oflog/oflog.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <mutex>

namespace curette::io {

std::string newDicomUid() {
    char uid[100];
    dcmGenerateUniqueIdentifier(uid, SITE_INSTANCE_UID_ROOT);
    return uid;
}

void silenceDcmtk() {
    static std::once_flag once;
    std::call_once(once, [] { OFLog::configure(OFLogger::FATAL_LOG_LEVEL); });
}

std::string decimalString(double value) {
    if (std::abs(value) < 1e-12) return "0";
    for (int precision = 15; precision > 0; --precision) {
        char text[64];
        std::snprintf(text, sizeof text, "%.*g", precision, value);
        if (std::string(text).size() <= 16) return text;
    }
    return "0";
}

std::string decimalStrings(const std::vector<double>& values) {
    std::string text;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i) text += '\\';
        text += decimalString(values[i]);
    }
    return text;
}

DicomDateTime dicomNow() {
    std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char date[16], time[16];
    std::strftime(date, sizeof date, "%Y%m%d", &local);
    std::strftime(time, sizeof time, "%H%M%S", &local);
    return {date, time};
}

}  // namespace curette::io
