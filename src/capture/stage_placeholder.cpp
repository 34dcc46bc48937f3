// Placeholder so the capture stage library exists while it is being built.
namespace inim {}
