// placeholder: filled by the integrator work
