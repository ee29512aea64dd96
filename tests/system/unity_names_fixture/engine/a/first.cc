namespace vesselid {
namespace {

constexpr double kShared = 1.0;

}  // namespace
}  // namespace vesselid
