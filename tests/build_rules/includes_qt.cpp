#include <QObject>  // must not compile: core has no Qt include path
int probe();
