"""rho of the lambda model per muscle: a group's published rho [N] (Payan & Perrier 1997,
SPEECHart; T and MH ours: controllers/ep_controller/muscle_rho.hpp) split over its muscles in
proportion to their F_max; the plan's rho overrides a group's."""
import tongue

DEFAULT_GROUP_RHO = {"GGp": 5.2, "GGm": 5.2, "GGa": 5.2, "HG": 21.7, "SG": 4.4,
                     "V": 2.4, "SL": 14.3, "IL": 19.4, "T": 15.6, "MH": 12.1}


def muscle_rhos(muscle_names, max_forces_n, overrides):
    """rho [N] per muscle (model order); overrides: [(muscle or group, group rho [N])].
    ValueError naming a muscle that has neither a default nor an override."""
    rho = [None] * len(muscle_names)

    def share(members, group_rho):
        total = 0.0
        for m in members:
            total += max_forces_n[m]
        for m in members:
            rho[m] = group_rho * max_forces_n[m] / total

    for m, name in enumerate(muscle_names):
        if rho[m] is not None:
            continue
        group = tongue.muscle_group(name)
        if group in DEFAULT_GROUP_RHO:
            share(tongue.select_muscles(group, muscle_names), DEFAULT_GROUP_RHO[group])
    for name, group_rho in overrides:
        share(tongue.select_muscles(name, muscle_names), group_rho)
    for m, name in enumerate(muscle_names):
        if rho[m] is None:
            raise ValueError(f"muscle {name} has no default rho (only the built-in tongue's "
                             "groups have one): give it in the plan's rho:")
    return rho
