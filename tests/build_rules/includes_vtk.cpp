#include <vtkActor.h>  // must not compile: core has no VTK include path
int probe();
