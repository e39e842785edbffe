/* ryushi — a material's constitutive model as the case describes it (materials[i].rheology):
 * the model and its constants. The models themselves (viscosity at a shear rate, the polymer
 * stress update) are in ryushi/rheology.h. */
#ifndef RYUSHI_MATERIAL_H
#define RYUSHI_MATERIAL_H

typedef enum {
    RY_RHEO_NEWTONIAN = 0,
    RY_RHEO_POWER_LAW,
    RY_RHEO_CARREAU,
    RY_RHEO_OLDROYD_B,
    RY_RHEO_GIESEKUS
} ry_rheo_model;

typedef struct ry_rheology {
    int model;
    double consistency, index; /* power law k [m^2 s^(n-2)], n; Carreau n */
    double nu_min, nu_max;     /* power law bounds [m^2/s] */
    double nu_zero, nu_inf;    /* Carreau [m^2/s] */
    double time;               /* Carreau time constant [s] */
    double nu_polymer;         /* Oldroyd-B, Giesekus [m^2/s] */
    double relaxation;         /* Oldroyd-B, Giesekus lambda [s] */
    double mobility;           /* Giesekus alpha */
} ry_rheology;

#endif
