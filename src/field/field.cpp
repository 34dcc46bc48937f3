// The Field interface is header-only; this unit anchors the stage's library.
#include "field/field.h"
