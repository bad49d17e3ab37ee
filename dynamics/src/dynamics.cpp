// The dynamics layer's translation units are added beside this one (docs/model.md §7).
namespace epicycle::dynamics {}
