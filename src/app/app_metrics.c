/* app_metrics: accuracy metrics of a world's state for `meadow bench`. */
#include "app/app_world.h"

void app_world_metrics(app_world_t *w, app_metrics_t *m)
{
    (void)w;
    (void)m;
}
