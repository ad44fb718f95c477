//! The points of a grid of parameters: the product of its axes.

/// Every point of the grid whose axes are `(name, values)`, in order, the first axis varying
/// slowest; each point is the `(name, value)` of every axis, in axis order.
pub fn product<N: Clone>(axes: &[(N, &[f64])]) -> Vec<Vec<(N, f64)>> {
    axes.iter()
        .fold(vec![Vec::new()], |points, (name, values)| {
            points
                .iter()
                .flat_map(|point| {
                    values.iter().map(move |&v| {
                        let mut q = point.clone();
                        q.push((name.clone(), v));
                        q
                    })
                })
                .collect()
        })
}
