namespace vesselid {
namespace {

constexpr double kShared = 2.0;

}  // namespace
}  // namespace vesselid
