// Placeholder so the radiance stage library exists while it is being built.
namespace inim {}
