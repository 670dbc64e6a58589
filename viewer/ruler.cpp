#include "viewer/ruler.h"

namespace curette {

void Ruler::place(const RulerPoint& p) {
    if (a_ && !b_) {
        b_ = p;
        return;
    }
    a_ = p;
    b_.reset();
}

std::optional<RulerLength> Ruler::length() const {
    if (!a_ || !b_) return std::nullopt;
    return RulerLength{glm::length(b_->world - a_->world), a_->uncertaintyMm + b_->uncertaintyMm};
}

}  // namespace curette
