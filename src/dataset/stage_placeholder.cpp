// Placeholder so the dataset stage library exists while it is being built.
namespace inim {}
